#include "run/picture_run.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include "report/output_files.hpp"
#include "report/progress.hpp"
#include "run/child_processes.hpp"
#include "run/execute_run.hpp"
#include "run/lockstep_driver.hpp"
#include "run/picture_driver.hpp"
#include "run/placement.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/sim/picture_run.hpp"
#include "skyfuse/sim/picture_truth.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {
namespace {

using Clock = std::chrono::steady_clock;
// Real time: step 0 begins this long after every node joined, so that the start tick reaches
// every node first (the single-target run's head start).
constexpr std::chrono::milliseconds kRealtimeHeadStart{1000};
// Real time: a round whose pictures have not all come this long after its scheduled end is
// handed over with those that did.
constexpr std::chrono::milliseconds kLateAfter{2000};

// What a run of many aircraft does not take yet, each with why; nothing if `o` is fine.
void refuse_what_a_picture_run_lacks(const RunOptions& o) {
  const auto refuse = [](const char* option) {
    throw std::invalid_argument(
        fmt::format("{}: not for a run of many aircraft yet (docs/multitarget.md says what "
                    "runs over DDS so far)",
                    option));
  };
  if (!o.replay_path.empty()) refuse("--replay");
  if (!o.record_path.empty()) refuse("--record");
  if (o.live) refuse("--live");
  if (o.external) refuse("--external");
  if (o.hosts > 0) refuse("--hosts");
  if (o.node.secure_dir) refuse("--secure");
  if (o.node.refusion_lag != 0) refuse("--refusion-lag");
}

std::string hex(std::uint64_t v) {
  return fmt::format("{:016x}", v);
}

// The center's picture against a peer's: rounds whose tracks (ids and statuses) differ, and the
// largest |x_center - x_p2p| / (1 + |x_center|) over the tracks both hold.
void compare_center(const wire::PictureRound& center, const wire::PictureRound& peer,
                    PictureRunSummary& summary) {
  const auto& mine = peer.tracks();
  const auto& theirs = center.tracks();
  bool same_tracks = mine.size() == theirs.size();
  for (std::size_t i = 0, j = 0; i < mine.size() && j < theirs.size();) {
    if (mine[i].track_id() < theirs[j].track_id()) {
      ++i;
    } else if (theirs[j].track_id() < mine[i].track_id()) {
      ++j;
    } else {
      same_tracks = same_tracks && mine[i].confirmed() == theirs[j].confirmed();
      double gap = 0.0;
      double norm = 0.0;
      for (std::size_t e = 0; e < theirs[j].x().size() && e < mine[i].x().size(); ++e) {
        gap += (theirs[j].x()[e] - mine[i].x()[e]) * (theirs[j].x()[e] - mine[i].x()[e]);
        norm += theirs[j].x()[e] * theirs[j].x()[e];
      }
      summary.max_state_gap_center_vs_p2p =
          std::max(summary.max_state_gap_center_vs_p2p, std::sqrt(gap) / (1.0 + std::sqrt(norm)));
      ++i;
      ++j;
    }
  }
  if (!same_tracks) ++summary.rounds_center_tracks_differ;
}

}  // namespace

PictureRunSummary execute_picture_run(const RunOptions& o, const Scenario& scenario) {
  refuse_what_a_picture_run_lacks(o);
  const PicturePlan plan = make_picture_plan(scenario, o.node.overrides);
  std::vector<int> ids;
  for (const StationConfig& s : plan.participants()) ids.push_back(s.id);
  std::sort(ids.begin(), ids.end());
  check_station_events(o, ids, plan.scenario.steps);

  // The in-process twin first: what every peer's picture must equal, round by round.
  const TrafficTruth truth = build_traffic_truth(plan.scenario, o.node.traffic_file);
  // The nodes read the scenario's copy in the results folder: a recorded file it names relative
  // to itself is passed to them by its absolute path.
  const auto recorded = recorded_traffic_file(plan.scenario, o.node.traffic_file);
  const PictureRunResult twin =
      run_picture(plan.scenario, truth.targets, plan.stations, plan.mc_run);

  const std::filesystem::path out(o.out_dir);
  std::filesystem::create_directories(out);
  const std::filesystem::path scenario_file = std::filesystem::absolute(out / "scenario.yaml");
  write_file_atomically(scenario_file, read_scenario_text(o.node.scenario_path));
  const std::uint64_t run_id = o.run_id.value_or(fresh_run_id());
  const double discovery_timeout =
      o.discovery_timeout_s.value_or(default_discovery_timeout_s(plan.stations));

  const Placement placement(o, plan.scenario.exchange, ids.size());
  std::vector<int> nodes = ids;  // the center (0) first, then the stations ascending
  nodes.insert(nodes.begin(), kCenterNodeId);
  ChildProcesses children;
  PictureDriver driver(harness_node_config(o, placement, plan.stations), run_id, nodes, children);
  try {
    // Process 0 is the center, process 1 + j the j-th station: each with the run's options.
    const auto spawn = [&](std::size_t process, std::vector<std::string> argv, int id) {
      options::NodeOptions child = o.node;
      child.network = placement.of(process).first;
      child.scenario_path = scenario_file.string();
      if (recorded) child.traffic_file = std::filesystem::absolute(*recorded).string();
      child.run_id = run_id;
      child.overrides.stations = plan.stations;
      child.overrides.steps = plan.scenario.steps;
      child.overrides.mc_run = plan.mc_run;
      child.discovery_timeout_s = discovery_timeout;
      child.idle_timeout_s = std::max(30.0, 3.0 * o.round_timeout_s);
      child.log_level = o.verbose ? "info" : "warn";
      const std::vector<std::string> common = options::to_arguments(child);
      argv.insert(argv.end(), common.begin(), common.end());
      children.spawn(node_name(id), argv);
    };
    const auto spawn_station = [&](int id, std::optional<int> rejoin_step) {
      const auto participants = plan.participants();
      const auto j = static_cast<std::size_t>(
          std::find_if(participants.begin(), participants.end(),
                       [&](const StationConfig& c) { return c.id == id; }) -
          participants.begin());
      std::vector<std::string> argv{(executable_dir() / "skyfuse-station").string(), "--id",
                                    std::to_string(id)};
      if (rejoin_step) {
        argv.push_back("--rejoin-at-step");
        argv.push_back(std::to_string(*rejoin_step));
      }
      spawn(1 + j, std::move(argv), id);
    };
    spawn(0, {(executable_dir() / "skyfuse-center").string()}, kCenterNodeId);
    for (const int id : ids) spawn_station(id, std::nullopt);
    const auto discovery_start = Clock::now();
    driver.wait_until_joined(std::chrono::milliseconds(std::llround(discovery_timeout * 1e3)));

    PictureRunSummary summary;
    summary.scenario = plan.scenario.name;
    summary.stations = plan.stations;
    summary.steps = plan.scenario.steps;
    summary.discovery_s = std::chrono::duration<double>(Clock::now() - discovery_start).count();
    std::ostringstream csv;
    csv << "step,station,picture_digest,tracks,confirmed,scans_fused,in_process_digest\n";
    Progress progress(fmt::format("picture M={}", plan.stations), plan.scenario.steps);
    const auto round_timeout = std::chrono::milliseconds(std::llround(o.round_timeout_s * 1e3));
    const auto start = Clock::now();
    int apart_at = -1;  // the last round found with peers apart
    // The first station's picture scored against the truth, as the in-process run scores its
    // peers' (GOSPA of the confirmed tracks against the aircraft present).
    PictureScore score(plan.scenario.traffic->gospa, truth.targets.size(),
                       plan.scenario.time_step_s);
    std::vector<TruthPoint> aircraft;
    std::vector<TrackPoint> confirmed_tracks;
    const int stations_up_all = plan.stations;
    // Everything a round's pictures are checked for: every station's against the others' and
    // its in-process twin's, the center's against its twin's and a peer's; the first station's
    // scored. `rounds`: the pictures that came, in node order (the center first).
    const auto check_round = [&](int k, const std::vector<wire::PictureRound>& rounds) {
      const auto step = static_cast<std::size_t>(k);
      const wire::PictureRound* center = nullptr;
      const wire::PictureRound* first_peer = nullptr;
      bool in_time = rounds.size() == ids.size() + 1;
      for (const wire::PictureRound& r : rounds) {
        if (r.source_id() == kCenterNodeId) {
          center = &r;
        } else if (first_peer == nullptr) {
          first_peer = &r;
        }
        if (r.source_id() != kCenterNodeId &&
            r.scans_fused() != static_cast<std::uint32_t>(stations_up_all)) {
          in_time = false;
        }
      }
      if (in_time) ++summary.rounds_in_time;
      for (const wire::PictureRound& r : rounds) {
        const bool is_center = r.source_id() == kCenterNodeId;
        const std::uint64_t expected =
            is_center ? twin.center_digests.at(step) : twin.peer_digests.at(step);
        const auto confirmed = std::count_if(r.tracks().begin(), r.tracks().end(),
                                             [](const auto& t) { return t.confirmed(); });
        csv << fmt::format("{},{},{},{},{},{},{}\n", k, r.source_id(), hex(r.picture_digest()),
                           r.tracks().size(), confirmed, r.scans_fused(), hex(expected));
        if (is_center) {
          if (r.picture_digest() != expected && summary.center_equals_in_process) {
            summary.center_equals_in_process = false;
            summary.first_step_center_apart_from_in_process = k;
          }
          continue;
        }
        if (r.picture_digest() != first_peer->picture_digest() && apart_at != k) {
          apart_at = k;
          ++summary.rounds_peers_apart;
          summary.last_round_peers_apart = k;
          if (summary.peers_identical) {
            summary.peers_identical = false;
            summary.first_divergent_step = k;
          }
        }
        if (r.picture_digest() != expected && summary.equals_in_process) {
          summary.equals_in_process = false;
          summary.first_step_apart_from_in_process = k;
        }
      }
      if (first_peer == nullptr) {
        ++summary.rounds_without_a_picture;
        return;
      }
      if (center != nullptr) compare_center(*center, *first_peer, summary);
      aircraft_at_step(plan.scenario, plan.stations, truth.targets, k, aircraft);
      confirmed_tracks.clear();
      for (const wire::PictureTrack& t : first_peer->tracks()) {
        if (t.confirmed()) {
          confirmed_tracks.push_back({t.track_id(), Vector3(t.x()[0], t.x()[1], t.x()[2])});
        }
      }
      score.add_step(k, aircraft, confirmed_tracks);
      if (k + 1 == plan.scenario.steps) {
        summary.tracks_at_end = first_peer->tracks().size();
        summary.confirmed_at_end = confirmed_tracks.size();
        summary.digest_at_end = first_peer->picture_digest();
      }
    };
    if (o.node.realtime_deadline_ms > 0.0) {
      const auto epoch = std::chrono::system_clock::now() + kRealtimeHeadStart;
      driver.run_realtime(plan.scenario.steps, plan.scenario.time_step_s, epoch, kLateAfter,
                          [&](int k, std::vector<wire::PictureRound> rounds) {
                            check_round(k, rounds);
                            progress.advance();
                          });
    } else {
      for (int k = 0; k < plan.scenario.steps; ++k) {
        for (const StationEvent& e : o.kills) {
          if (e.step != static_cast<std::uint64_t>(k)) continue;
          children.kill_now(node_name(e.station_id));
          driver.set_down(e.station_id, true);
          spdlog::info("killed station {} before step {}", e.station_id, k);
        }
        for (const StationEvent& e : o.restarts) {
          if (e.step != static_cast<std::uint64_t>(k)) continue;
          spawn_station(e.station_id, k);
          driver.wait_until_ready(e.station_id,
                                  std::chrono::milliseconds(std::llround(discovery_timeout * 1e3)));
          driver.set_down(e.station_id, false);
          spdlog::info("restarted station {} before step {}", e.station_id, k);
        }
        check_round(k, driver.run_round(static_cast<std::uint32_t>(k), round_timeout));
        progress.advance();
      }
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    summary.rounds_per_s = plan.scenario.steps / seconds;
    summary.loss = o.node.loss.enabled();
    summary.faults = summary.loss || !o.kills.empty();
    summary.realtime = o.node.realtime_deadline_ms > 0.0;
    summary.gospa_mean = score.summary().gospa_mean;
    summary.in_process_gospa_mean = twin.score.gospa_mean;
    for (const auto& [id, counts] : driver.wait_finished(std::chrono::seconds(5))) {
      if (id != kCenterNodeId) summary.resyncs += counts.first;
      summary.lost += counts.second;
    }
    driver.release();
    if (!children.wait_all(std::chrono::seconds(10))) {
      spdlog::warn("station processes still running 10 s after the run; stopping them");
      children.terminate_all(std::chrono::seconds(2));
    }

    write_file_atomically(out / "picture_rounds.csv", csv.str());
    nlohmann::json json = {
        {"scenario", summary.scenario},
        {"stations", summary.stations},
        {"steps", summary.steps},
        {"run_id", run_id},
        {"peers_identical", summary.peers_identical},
        {"first_divergent_step", summary.first_divergent_step},
        {"rounds_peers_apart", summary.rounds_peers_apart},
        {"realtime", summary.realtime},
        {"rounds_in_time", summary.rounds_in_time},
        {"share_of_rounds_in_time", static_cast<double>(summary.rounds_in_time) / summary.steps},
        {"rounds_without_a_picture", summary.rounds_without_a_picture},
        {"last_round_peers_apart", summary.last_round_peers_apart},
        {"loss", summary.loss},
        {"faults", summary.faults},
        {"samples_lost", summary.lost},
        {"resyncs", summary.resyncs},
        {"gospa_mean", summary.gospa_mean},
        {"equals_in_process", summary.equals_in_process},
        {"first_step_apart_from_in_process", summary.first_step_apart_from_in_process},
        {"center_equals_in_process", summary.center_equals_in_process},
        {"first_step_center_apart_from_in_process",
         summary.first_step_center_apart_from_in_process},
        {"max_state_gap_center_vs_p2p", summary.max_state_gap_center_vs_p2p},
        {"rounds_center_tracks_differ", summary.rounds_center_tracks_differ},
        {"discovery_s", summary.discovery_s},
        {"rounds_per_s", summary.rounds_per_s},
        {"tracks_at_end", summary.tracks_at_end},
        {"confirmed_at_end", summary.confirmed_at_end},
        {"picture_digest_at_end", hex(summary.digest_at_end)},
        {"in_process",
         {{"peers_identical", twin.peers_identical},
          {"confirmed_at_end", twin.confirmed_at_end},
          {"max_state_gap_center_vs_p2p", twin.max_state_gap},
          {"association_flips", twin.association_flips},
          {"gospa_mean", twin.score.gospa_mean}}}};
    write_file_atomically(out / "summary.json", json.dump(2) + "\n");
    return summary;
  } catch (...) {
    children.terminate_all(std::chrono::seconds(2));
    throw;
  }
}

void print_picture_run_table(const PictureRunSummary& s, std::FILE* out) {
  fmt::print(out,
             "many aircraft over DDS: scenario '{}', {} station processes and the center, {} "
             "rounds\n",
             s.scenario, s.stations, s.steps);
  const auto row = [&](std::string_view what, const std::string& value) {
    fmt::print(out, "  {:<36} {}\n", what, value);
  };
  row("peers' pictures",
      s.peers_identical
          ? "bit-identical in every round"
          : fmt::format("apart in {} rounds ({}-{}), bit-identical in the others",
                        s.rounds_peers_apart, s.first_divergent_step, s.last_round_peers_apart));
  if (s.loss) {
    row("samples lost (--loss)",
        fmt::format("{}; {} rounds a station took the lowest station's picture", s.lost,
                    s.resyncs));
  }
  row("peers equal to the in-process run",
      s.equals_in_process ? "yes, every round"
                          : fmt::format("no, from round {}", s.first_step_apart_from_in_process));
  row("center equal to its in-process run",
      s.center_equals_in_process
          ? "yes, every round"
          : fmt::format("no, from round {}", s.first_step_center_apart_from_in_process));
  row("center vs peer-to-peer",
      fmt::format("max |dx| / (1 + |x|) {:.2e}; {} rounds with other "
                  "tracks",
                  s.max_state_gap_center_vs_p2p, s.rounds_center_tracks_differ));
  row(s.realtime ? "rounds in time" : "rounds with every scan fused",
      fmt::format(
          "{} of {} ({:.1f} %){}", s.rounds_in_time, s.steps, 100.0 * s.rounds_in_time / s.steps,
          s.rounds_without_a_picture > 0
              ? fmt::format("; {} rounds without any station's picture", s.rounds_without_a_picture)
              : std::string()));
  row("tracks at the end", fmt::format("{} ({} confirmed)", s.tracks_at_end, s.confirmed_at_end));
  row("GOSPA, mean over rounds", fmt::format("{:.2f} (the in-process run, without faults: {:.2f})",
                                             s.gospa_mean, s.in_process_gospa_mean));
  row("discovery", fmt::format("{:.2f} s", s.discovery_s));
  row("rounds per second", fmt::format("{:.0f}", s.rounds_per_s));
}

}  // namespace skyfuse::harness
