// A client nobody on the project wrote: skyfuse-cyclone-tracks (interop/), a Cyclone DDS reader
// in C whose types come from Cyclone's idlc on idl/skyfuse_wire.idl, against a real run. One
// reader is there from the start and must receive every track, equal to tracks.csv bit for bit;
// a second joins mid-run as a viewer would and must get each source's latest track at once,
// from the writers' durable history, before that source writes its next one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cinttypes>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "integration/run_fixture.hpp"
#include "skyfuse/picture/picture_digest.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;

constexpr int kDomain = 201;
constexpr int kStations = 4;
constexpr int kSources = kStations + 1;  // and the center
constexpr int kSteps = 20;
constexpr int kPictureDomain = 202;

// A line of the reader's CSV:
//   step,source,track,number,status,settled,written_ns,matched_ns,received_ns,n,x0..,p0_0,..
// status "deleted": a disposed track, with only source, track and the times.
struct ReceivedTrack {
  int step = -1;
  int source = 0;
  std::uint64_t track = 0;
  unsigned number = 0;  // the short track number; 0: none
  std::string status;
  bool settled = false;
  long long written_ns = 0;
  long long matched_ns = 0;  // when the reader matched the writer
  long long received_ns = 0;
  std::vector<double> x;
  std::vector<double> covariance;  // the upper triangle, row by row
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
    if (!f.empty()) t.step = std::stoi(f);
    std::getline(fields, f, ',');
    t.source = std::stoi(f);
    std::getline(fields, f, ',');
    t.track = std::stoull(f);
    std::getline(fields, f, ',');
    t.number = static_cast<unsigned>(std::stoul(f));
    std::getline(fields, t.status, ',');
    std::getline(fields, f, ',');
    t.settled = f == "1";
    std::getline(fields, f, ',');
    t.written_ns = std::stoll(f);
    std::getline(fields, f, ',');
    t.matched_ns = std::stoll(f);
    std::getline(fields, f, ',');
    t.received_ns = std::stoll(f);
    std::getline(fields, f, ',');
    const std::size_t n = std::stoul(f);
    while (std::getline(fields, f, ',')) {
      (t.x.size() < n ? t.x : t.covariance).push_back(std::strtod(f.c_str(), nullptr));
    }
    EXPECT_EQ(t.covariance.size(), n * (n + 1) / 2) << line;
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
      EXPECT_EQ(t.track, 0u) << file;  // one aircraft: its track 0, confirmed, no number
      EXPECT_EQ(t.number, 0u) << file;
      EXPECT_EQ(t.status, "confirmed") << file;
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

// Three aircraft over four radars with clutter; the second leaves after 5 s, so its tracks are
// dropped after 5 misses and their instances disposed. Scans every 0.5 s on the wall clock, so
// that the reader, which matches each writer as it appears, has matched them all before the
// first round (a writer keeps only each track's latest sample for a reader that comes late).
constexpr const char* kPictureScenario = R"(name: interop-picture
seed: 20261127
time_step_s: 0.5
steps: 30
traffic:
  targets:
    - {initial_position_m: [-2000.0, -1500.0, 300.0], heading_deg: 30.0, speeds_kmh: [120]}
    - {initial_position_m: [1500.0, 0.0, 200.0], heading_deg: 180.0, speeds_kmh: [90],
       leaves_s: 5.0}
    - {initial_position_m: [0.0, 2500.0, 400.0], heading_deg: 270.0, speeds_kmh: [150],
       appears_s: 2.5}
detection:
  probability: 0.9
  max_range_m: 12000.0
  min_elevation_deg: 0.0
  clutter_per_scan: 2.0
tracker:
  confirm: [2, 3]
  delete_after_misses: 5
  initiation: {min_stations: 2, velocity_std_mps: 60.0}
)";

// A node's row of picture_rounds.csv.
struct PictureRow {
  std::uint64_t digest = 0;
  std::size_t tracks = 0;
  std::size_t confirmed = 0;
};

std::map<std::pair<int, int>, PictureRow> read_picture_rounds(const std::filesystem::path& csv) {
  std::map<std::pair<int, int>, PictureRow> rows;  // (step, node)
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("step,station,picture_digest,tracks,confirmed,", 0), 0u) << line;
  while (std::getline(in, line)) {
    int step = 0;
    int node = 0;
    PictureRow row;
    EXPECT_EQ(std::sscanf(line.c_str(), "%d,%d,%" SCNx64 ",%zu,%zu", &step, &node, &row.digest,
                          &row.tracks, &row.confirmed),
              5)
        << line;
    rows[{step, node}] = row;
  }
  return rows;
}

// The digest of the tracks a reader received for one node and round, computed as the node
// computes its own (PictureDigest): ascending track id, the covariance made whole from its
// upper triangle (the pictures' covariances are symmetric bit for bit).
std::uint64_t digest_of(std::vector<const ReceivedTrack*> tracks) {
  std::sort(tracks.begin(), tracks.end(),
            [](const ReceivedTrack* a, const ReceivedTrack* b) { return a->track < b->track; });
  PictureDigest digest(tracks.size());
  for (const ReceivedTrack* t : tracks) {
    const auto n = static_cast<Eigen::Index>(t->x.size());
    const Eigen::VectorXd mean = Eigen::Map<const Eigen::VectorXd>(t->x.data(), n);
    Eigen::MatrixXd covariance(n, n);
    std::size_t k = 0;
    for (Eigen::Index r = 0; r < n; ++r) {
      for (Eigen::Index c = r; c < n; ++c) covariance(r, c) = covariance(c, r) = t->covariance[k++];
    }
    digest.add(t->track,
               t->status == "confirmed" ? TrackStatus::kConfirmed : TrackStatus::kTentative, mean,
               covariance);
  }
  return digest.value();
}

TEST(DdsInterop, ACycloneDdsReaderHoldsEveryNodesPictureAndALateOneTheLatestAtOnce) {
  const std::string reader = bin("skyfuse-cyclone-tracks");
  if (!std::filesystem::exists(reader)) {
    GTEST_SKIP() << "Cyclone DDS was not found when the build was configured";
  }
  const auto dir = test_dir();
  std::ofstream(dir / "picture.yaml") << kPictureScenario << kFourRadarsAndAnEkf;
  const std::string domain = std::to_string(kPictureDomain);
  Process cyclone(
      {reader, "--domain", domain, "--out", (dir / "every.csv").string(), "--timeout-s", "150"},
      dir / "every.log");
  Process run({bin("skyfuse"), "run", "--scenario", (dir / "picture.yaml").string(), "--domain",
               domain, "--realtime-deadline-ms", "200", "--out", (dir / "run").string()},
              dir / "run.log");
  // A viewer that joins mid-run, while the first reader reads: a third of the run's tracks in.
  ASSERT_TRUE(eventually([&] { return lines_in(dir / "every.csv") > 120; }, 60s))
      << run.output() << cyclone.output();
  Process late({reader, "--domain", domain, "--latest", std::to_string(kSources), "--out",
                (dir / "late.csv").string(), "--timeout-s", "60"},
               dir / "late.log");
  const auto run_status = run.wait(120s);
  ASSERT_TRUE(run_status && run_status->code == 0) << run.output();
  const auto late_status = late.wait(60s);
  ASSERT_TRUE(late_status && late_status->code == 0) << late.output();
  const auto cyclone_status = cyclone.wait(60s);
  ASSERT_TRUE(cyclone_status && cyclone_status->code == 0) << cyclone.output();

  const auto rounds = read_picture_rounds(dir / "run" / "picture_rounds.csv");
  ASSERT_EQ(rounds.size(), 30u * 5u);  // 30 rounds, 4 stations and the center
  const ReaderOutput received = read_reader_output(dir / "every.csv");
  std::map<std::pair<int, int>, std::vector<const ReceivedTrack*>> tracks;  // (step, node)
  std::set<std::pair<int, std::uint64_t>> deleted;                          // (node, track)
  for (const ReceivedTrack& t : received.tracks) {
    if (t.status == "deleted") {
      EXPECT_TRUE(deleted.insert({t.source, t.track}).second) << "track disposed twice";
    } else {
      tracks[{t.step, t.source}].push_back(&t);
    }
  }

  // A node writes its tracks while a reader is matched: from the first round after it matched
  // this one, which on the wall clock at 0.5 s a round is the first round or the next.
  std::map<int, int> first_round;  // node -> the first round the reader got from it
  for (const auto& [key, got] : tracks) {
    if (!first_round.contains(key.second)) first_round[key.second] = key.first;
  }
  ASSERT_EQ(first_round.size(), 5u) << "a node's tracks never reached the reader";
  for (const auto& [node, step] : first_round) EXPECT_LE(step, 1) << "node " << node;

  // From then on every node's picture of every round, whole and bit for bit: its digest is
  // the node's.
  for (const auto& [key, row] : rounds) {
    const auto& [step, node] = key;
    if (step < first_round[node]) continue;
    const auto& got = tracks[key];
    EXPECT_EQ(got.size(), row.tracks) << "step " << step << " node " << node;
    EXPECT_EQ(std::count_if(got.begin(), got.end(),
                            [](const ReceivedTrack* t) { return t->status == "confirmed"; }),
              static_cast<long>(row.confirmed))
        << "step " << step << " node " << node;
    EXPECT_EQ(digest_of(got), row.digest) << "step " << step << " node " << node;
  }
  for (const auto& [key, got] : tracks) {
    EXPECT_TRUE(rounds.contains(key)) << "tracks of a round the run did not have";
  }

  // Each track with its short number, the same at every node of a round, one number a track.
  std::map<std::pair<int, std::uint64_t>, unsigned> number_of;  // (step, track) -> number
  for (const auto& [key, got] : tracks) {
    std::set<unsigned> in_round;
    for (const ReceivedTrack* t : got) {
      EXPECT_GT(t->number, 0u) << "step " << key.first << " track " << t->track;
      EXPECT_TRUE(in_round.insert(t->number).second) << "a number given twice, step " << key.first;
      const auto [at, first] = number_of.emplace(std::pair{key.first, t->track}, t->number);
      EXPECT_EQ(at->second, t->number) << "step " << key.first << ": nodes number alike";
    }
  }

  // A track in a node's picture that the next round's does not hold was disposed; none other.
  std::set<std::pair<int, std::uint64_t>> dropped;
  for (const auto& [key, row] : rounds) {
    const auto& [step, node] = key;
    if (step < first_round[node]) continue;
    const auto next = tracks.find({step + 1, node});
    if (next == tracks.end()) continue;
    for (const ReceivedTrack* t : tracks[key]) {
      const bool kept = std::any_of(next->second.begin(), next->second.end(),
                                    [&](const ReceivedTrack* u) { return u->track == t->track; });
      if (!kept) dropped.insert({node, t->track});
    }
  }
  EXPECT_FALSE(dropped.empty()) << "the aircraft that left was never dropped: nothing tested";
  EXPECT_EQ(deleted, dropped);

  // The viewer that joined: from each node's writer history, the node's whole picture of the
  // round before it matched (its digest the node's), then the next round's tracks live.
  const ReaderOutput joined = read_reader_output(dir / "late.csv");
  for (int node = 0; node < kSources; ++node) {
    std::map<int, std::vector<const ReceivedTrack*>> history;  // step -> tracks
    int first_live = -1;
    for (const ReceivedTrack& t : joined.tracks) {
      if (t.source != node || t.status == "deleted") continue;
      if (t.written_ns < t.matched_ns) {
        history[t.step].push_back(&t);
      } else if (first_live < 0 || t.step < first_live) {
        first_live = t.step;
      }
    }
    ASSERT_EQ(history.size(), 1u) << "node " << node << ": the history held one round's tracks";
    const auto& [step, got] = *history.begin();
    EXPECT_GT(step, 0) << "node " << node << ": not joined mid-run";
    const auto row = rounds.find({step, node});
    ASSERT_NE(row, rounds.end());
    EXPECT_EQ(got.size(), row->second.tracks) << "node " << node << ", round " << step;
    EXPECT_EQ(digest_of(got), row->second.digest) << "node " << node << ", round " << step;
    EXPECT_EQ(first_live, step + 1) << "node " << node << ": the history was not its latest";
  }
}

}  // namespace
}  // namespace skyfuse::test
