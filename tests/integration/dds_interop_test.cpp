// A client nobody on the project wrote: skyfuse-cyclone-tracks (interop/), a Cyclone DDS reader
// in C whose types come from Cyclone's idlc on idl/skyfuse_wire.idl, against a real run. One
// reader is there from the start and must receive every track, equal to tracks.csv bit for bit;
// a second joins mid-run as a viewer would and must get each source's latest track at once,
// from the writers' durable history, before that source writes its next one.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "integration/run_fixture.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;

constexpr int kDomain = 201;
constexpr int kStations = 4;
constexpr int kSources = kStations + 1;  // and the center
constexpr int kSteps = 20;

// A line of the reader's CSV: step,source,settled,written_ns,matched_ns,received_ns,x0,x1,...
struct ReceivedTrack {
  int step = 0;
  int source = 0;
  bool settled = false;
  long long written_ns = 0;
  long long matched_ns = 0;  // when the reader matched the writer
  long long received_ns = 0;
  std::vector<double> x;
};

struct ReaderOutput {
  long long joined_ns = 0;
  std::vector<ReceivedTrack> tracks;
};

ReaderOutput read_reader_output(const std::filesystem::path& csv) {
  ReaderOutput out;
  std::ifstream in(csv);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# joined_ns=", 0) == 0) {
      out.joined_ns = std::stoll(line.substr(std::strlen("# joined_ns=")));
      continue;
    }
    std::istringstream fields(line);
    std::string f;
    ReceivedTrack t;
    std::getline(fields, f, ',');
    t.step = std::stoi(f);
    std::getline(fields, f, ',');
    t.source = std::stoi(f);
    std::getline(fields, f, ',');
    t.settled = f == "1";
    std::getline(fields, f, ',');
    t.written_ns = std::stoll(f);
    std::getline(fields, f, ',');
    t.matched_ns = std::stoll(f);
    std::getline(fields, f, ',');
    t.received_ns = std::stoll(f);
    while (std::getline(fields, f, ',')) t.x.push_back(std::strtod(f.c_str(), nullptr));
    out.tracks.push_back(std::move(t));
  }
  return out;
}

int lines_in(const std::filesystem::path& file) {
  std::ifstream in(file);
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

// Nothing if `t` carries tracks.csv's state for its (step, source) bit for bit.
std::optional<std::string> difference_from_csv(const ReceivedTrack& t, const TrackRows& csv) {
  const auto row = csv.find({t.step, t.source});
  const std::string where =
      "step " + std::to_string(t.step) + " source " + std::to_string(t.source);
  if (row == csv.end()) return where + ": not in tracks.csv";
  if (t.x.size() != row->second.size())
    return where + ": " + std::to_string(t.x.size()) + " values";
  if (std::memcmp(t.x.data(), row->second.data(), sizeof(double) * t.x.size()) != 0) {
    return where + ": other bits than tracks.csv";
  }
  return std::nullopt;
}

TEST(DdsInterop, ACycloneDdsReaderGetsEveryTrackAndALateJoinerEachSourcesLatestAtOnce) {
  const std::string reader = bin("skyfuse-cyclone-tracks");
  if (!std::filesystem::exists(reader)) {
    GTEST_SKIP() << "Cyclone DDS (Debian's cyclonedds-dev and cyclonedds-tools) was not found "
                    "when the build was configured: skyfuse-cyclone-tracks was not built";
  }
  const auto dir = test_dir();
  // Real time at dt = 0.5 s, so that the late reader joins between two rounds and the writers'
  // history reaches it before the next round even if a sample of it is lost and repaired at the
  // writer's next heartbeat (100 ms): at 0.2 s, on a loaded CI machine, a source's history once
  // came after its next track, and the KEEP_LAST 1 cache kept only that. Paper 000 with the
  // time step changed, 20 steps in 10 s.
  std::string scenario =
      read_file(std::filesystem::path(SKYFUSE_SOURCE_DIR) / "scenarios" / "paper000.yaml");
  const std::string dt_line = "time_step_s: 0.02\n";
  ASSERT_NE(scenario.find(dt_line), std::string::npos);
  scenario.replace(scenario.find(dt_line), dt_line.size(), "time_step_s: 0.5\n");
  std::ofstream(dir / "slow.yaml") << scenario;

  const std::string domain = std::to_string(kDomain);
  Process early(
      {reader, "--domain", domain, "--out", (dir / "every.csv").string(), "--timeout-s", "120"},
      dir / "every.log");
  // A reader given no configuration at all: Cyclone picks the interface (on these machines not
  // loopback) and discovers the run anyway (docs/interop.md).
  Process unconfigured({reader, "--domain", domain, "--cyclone-defaults", "--out",
                        (dir / "unconfigured.csv").string(), "--timeout-s", "120"},
                       dir / "unconfigured.log");
  Process run({bin("skyfuse"), "run", "--scenario", (dir / "slow.yaml").string(), "--stations",
               std::to_string(kStations), "--steps", std::to_string(kSteps), "--domain", domain,
               "--realtime-deadline-ms", "100", "--out", (dir / "run").string()},
              dir / "run.log");
  // Mid-run: once the first reader holds a third of the run.
  ASSERT_TRUE(
      eventually([&] { return lines_in(dir / "every.csv") > 1 + kSources * kSteps / 3; }, 60s))
      << run.output() << early.output();
  Process late({reader, "--domain", domain, "--latest", std::to_string(kSources), "--out",
                (dir / "late.csv").string(), "--timeout-s", "60"},
               dir / "late.log");

  const auto run_status = run.wait(120s);
  ASSERT_TRUE(run_status && run_status->code == 0) << run.output();
  const auto late_status = late.wait(60s);
  ASSERT_TRUE(late_status && late_status->code == 0) << late.output();
  const auto early_status = early.wait(60s);
  ASSERT_TRUE(early_status && early_status->code == 0) << early.output();
  const auto unconfigured_status = unconfigured.wait(60s);
  ASSERT_TRUE(unconfigured_status && unconfigured_status->code == 0) << unconfigured.output();

  const TrackRows csv = read_tracks(dir / "run" / "tracks.csv");
  ASSERT_EQ(csv.size(), static_cast<std::size_t>(kSources * kSteps));

  // Every track, once, bit for bit, whether the reader was pinned to loopback or not.
  for (const char* file : {"every.csv", "unconfigured.csv"}) {
    const ReaderOutput every = read_reader_output(dir / file);
    std::map<std::pair<int, int>, int> seen;
    for (const ReceivedTrack& t : every.tracks) {
      EXPECT_FALSE(t.settled);
      EXPECT_EQ(difference_from_csv(t, csv), std::nullopt) << file;
      ++seen[{t.step, t.source}];
    }
    EXPECT_EQ(seen.size(), csv.size()) << file;
    for (const auto& [key, count] : seen) {
      EXPECT_EQ(count, 1) << file << " " << key.first << "," << key.second;
    }
  }

  // The late joiner. A track written before its writer matched the reader came from the
  // writer's history: a volatile writer would never send it. For each source, the newest such
  // track must be the latest there was - the first track written after the match is the next
  // step - and it must have come before that next step was written.
  const ReaderOutput joined = read_reader_output(dir / "late.csv");
  for (int source = 0; source <= kStations; ++source) {
    const ReceivedTrack* newest_history = nullptr;
    const ReceivedTrack* first_live = nullptr;
    for (const ReceivedTrack& t : joined.tracks) {
      if (t.source != source) continue;
      EXPECT_FALSE(t.settled);
      EXPECT_NE(t.matched_ns, 0);
      EXPECT_EQ(difference_from_csv(t, csv), std::nullopt);
      if (t.written_ns < t.matched_ns) {
        if (newest_history == nullptr || t.step > newest_history->step) newest_history = &t;
      } else if (first_live == nullptr || t.step < first_live->step) {
        first_live = &t;
      }
    }
    ASSERT_NE(newest_history, nullptr)
        << "source " << source << ": nothing from the writer's history reached the late joiner";
    ASSERT_NE(first_live, nullptr) << "source " << source << " wrote nothing after the match";
    EXPECT_EQ(first_live->step, newest_history->step + 1)
        << "source " << source << ": the history did not hold its latest track";
    EXPECT_LT(newest_history->received_ns, first_live->written_ns)
        << "source " << source << ": its latest track came only after it wrote the next one";
    EXPECT_GT(newest_history->step, 0) << "source " << source << ": not joined mid-run";
  }
}

}  // namespace
}  // namespace skyfuse::test
