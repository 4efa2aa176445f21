#include "integration/run_fixture.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "skyfuse/scenario/scenario_loader.hpp"

namespace skyfuse::test {

namespace {

std::vector<std::string> split_csv_row(const std::string& row) {
  std::vector<std::string> fields;
  std::istringstream in(row);
  for (std::string f; std::getline(in, f, ',');) fields.push_back(f);
  return fields;
}

// tracks.csv's rows, live or settled, keyed by (step, source): the x<i> columns, or the p<i>_<j>
// columns filled into a symmetric matrix's entries row by row.
TrackRows read_track_columns(const std::filesystem::path& csv, char prefix, bool settled) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_csv_row(line);
  const auto settled_at = std::find(header.begin(), header.end(), "settled") - header.begin();
  std::vector<std::size_t> wanted;
  for (std::size_t i = 2; i < header.size(); ++i) {
    if (header[i][0] == prefix) wanted.push_back(i);
  }
  TrackRows tracks;
  while (std::getline(in, line)) {
    const std::vector<std::string> fields = split_csv_row(line);
    if ((fields.at(static_cast<std::size_t>(settled_at)) == "1") != settled) continue;
    StateRow row;
    for (std::size_t i : wanted) row.push_back(std::strtod(fields.at(i).c_str(), nullptr));
    tracks[{std::stoi(fields[0]), std::stoi(fields[1])}] = row;
  }
  return tracks;
}

}  // namespace

TrackRows read_tracks(const std::filesystem::path& csv) {
  return read_track_columns(csv, 'x', false);
}

TrackRows read_settled_tracks(const std::filesystem::path& csv) {
  return read_track_columns(csv, 'x', true);
}

TrackRows read_track_covariances(const std::filesystem::path& csv) {
  return read_track_columns(csv, 'p', false);
}

std::vector<double> steps_column(const std::filesystem::path& steps_csv, const std::string& name) {
  std::ifstream in(steps_csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_csv_row(line);
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) throw std::runtime_error(steps_csv.string() + ": no column " + name);
  const auto column = static_cast<std::size_t>(it - header.begin());
  std::vector<double> values;
  while (std::getline(in, line)) values.push_back(std::stod(split_csv_row(line).at(column)));
  return values;
}

std::vector<double> peer_spread(const std::filesystem::path& steps_csv) {
  return steps_column(steps_csv, "peer_spread");
}

void expect_peers_differ_only_around_the_loss(const std::filesystem::path& steps_csv, int steps,
                                              int loss_from, int loss_to, int agree_from) {
  const std::vector<double> spread = peer_spread(steps_csv);
  ASSERT_EQ(spread.size(), static_cast<std::size_t>(steps));
  for (int k = 0; k < loss_from; ++k) EXPECT_EQ(spread[k], 0.0) << k;
  EXPECT_GT(*std::max_element(spread.begin() + loss_from, spread.begin() + loss_to), 0.0);
  for (int k = agree_from; k < steps; ++k) EXPECT_EQ(spread[k], 0.0) << k;
}

TwinTracks in_process_twin(const RunPlan& plan, const NisGate& gate, RunTrace* trace) {
  TwinTracks twin;
  RunTrace t = simulate_run(
      plan.scenario, plan.truth(), plan.stations, plan.mc_run,
      [&](const StepRecord& r) { twin.emplace_back(r.central.mean, r.decentralised.mean); }, gate);
  if (trace != nullptr) *trace = std::move(t);
  return twin;
}

std::optional<std::string> difference_from_twin(const TrackRows& tracks, const RunPlan& plan,
                                                const TwinTracks& twin) {
  const auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  for (std::size_t k = 0; k < twin.size(); ++k) {
    const int step = static_cast<int>(k);
    const auto central = tracks.find({step, 0});
    if (central == tracks.end()) return "step " + std::to_string(k) + ": no central track";
    if (central->second.size() != static_cast<std::size_t>(twin[k].first.size())) {
      return "step " + std::to_string(k) + ": central track of " +
             std::to_string(central->second.size()) + " entries, in-process " +
             std::to_string(twin[k].first.size());
    }
    for (int i = 0; i < twin[k].first.size(); ++i) {
      if (!same_bits(central->second[static_cast<std::size_t>(i)], twin[k].first(i))) {
        return "step " + std::to_string(k) + ": central x" + std::to_string(i) + " DDS " +
               std::to_string(central->second[static_cast<std::size_t>(i)]) + " in-process " +
               std::to_string(twin[k].first(i));
      }
    }
    for (const StationConfig& s : plan.participants()) {
      const auto peer = tracks.find({step, s.id});
      if (peer == tracks.end()) {
        return "step " + std::to_string(k) + ": no track of station " + std::to_string(s.id);
      }
      if (peer->second.size() != static_cast<std::size_t>(twin[k].second.size())) {
        return "step " + std::to_string(k) + ": station " + std::to_string(s.id) +
               " track of another dimension";
      }
      for (int i = 0; i < twin[k].second.size(); ++i) {
        if (!same_bits(peer->second[static_cast<std::size_t>(i)], twin[k].second(i))) {
          return "step " + std::to_string(k) + ": station " + std::to_string(s.id) + " x" +
                 std::to_string(i) + " differs from the in-process run";
        }
      }
    }
  }
  return std::nullopt;
}

nlohmann::json expect_default_run_equals_twin(const std::filesystem::path& out, int stations,
                                              int steps) {
  const RunPlan plan = make_run_plan(load_default_scenario(), stations_and_steps(stations, steps));
  const auto tracks = read_tracks(out / "tracks.csv");
  EXPECT_EQ(tracks.size(), static_cast<std::size_t>(steps * (stations + 1)));
  EXPECT_EQ(difference_from_twin(tracks, plan, in_process_twin(plan)), std::nullopt);
  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary.at("max_abs_diff_between_peers"), 0.0);
  for (const auto& [kind, count] : summary.at("dropped_by_kind").items()) {
    EXPECT_EQ(count.get<int>(), 0) << kind;
  }
  return summary;
}

std::unique_ptr<Process> start_long_run(int domain, int stations, const std::filesystem::path& dir,
                                        const std::vector<std::string>& extra,
                                        std::chrono::seconds started_within) {
  std::vector<std::string> args = {bin("skyfuse"), "run",
                                   "--stations",   std::to_string(stations),
                                   "--steps",      "1000000",
                                   "--domain",     std::to_string(domain),
                                   "--out",        (dir / "out").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  auto run = std::make_unique<Process>(args, dir / "harness.log");
  const bool started =
      eventually([&] { return run->output().find("%]") != std::string::npos; }, started_within);
  EXPECT_TRUE(started) << run->output();
  return run;
}

void expect_refusals_listed_as_reported(const std::filesystem::path& out,
                                        const nlohmann::json& summary, int steps) {
  std::istringstream csv(read_file(out / "refusals.csv"));
  std::string line;
  std::getline(csv, line);
  ASSERT_EQ(line, "reported,node,step,kind,count");
  std::map<std::string, std::map<std::string, int>> listed;
  std::set<std::string> reported_during_run;
  while (std::getline(csv, line)) {
    std::istringstream row(line);
    std::string reported, node, step, kind, count;
    std::getline(row, reported, ',');
    std::getline(row, node, ',');
    std::getline(row, step, ',');
    std::getline(row, kind, ',');
    std::getline(row, count, ',');
    const std::string name = node == "0" ? "center" : node == "-1" ? "harness" : node;
    listed[name][kind] += std::stoi(count);
    if (std::stoi(reported) < steps) reported_during_run.insert(name);
  }
  std::map<std::string, std::map<std::string, int>> expected;
  for (const auto& [node, counts] : summary["dropped_by_node"].items()) {
    for (const auto& [kind, count] : counts.items()) {
      if (count.get<int>() > 0) expected[node][kind] = count.get<int>();
    }
  }
  EXPECT_EQ(listed, expected);
  for (const auto& [node, counts] : expected) {
    EXPECT_TRUE(reported_during_run.contains(node)) << node;
  }
}

}  // namespace skyfuse::test
