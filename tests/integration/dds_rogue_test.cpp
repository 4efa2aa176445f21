// A rogue process inside the run's domain publishes every malformed kind on the real increment
// and measurement topics, of a radar run and of a TDOA (NCRKF) run. Nothing it sends may be fused -
// the tracks equal those of the same run without it, bit for bit - and every receiver counts each
// kind it was sent.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "integration/run_fixture.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

constexpr int kAttackSteps = 3;  // the rogue's default steps 5, 10 and 15 of the run's 60

// A run to attack: its scenario (empty: the embedded default) and its stations, ascending.
struct Target {
  std::string scenario;
  std::vector<std::string> stations;
};

std::vector<std::string> run_args(const Target& target, int domain,
                                  const std::filesystem::path& out) {
  std::vector<std::string> args = {bin("skyfuse"), "run",
                                   "--stations",   std::to_string(target.stations.size()),
                                   "--steps",      "60",
                                   "--run-id",     "8086",
                                   "--domain",     std::to_string(domain),
                                   "--out",        out.string()};
  if (!target.scenario.empty()) args.insert(args.end(), {"--scenario", target.scenario});
  return args;
}

// Runs `target` clean and again with the rogue impersonating its first station, and checks that
// the tracks are the same bytes and that every receiver counted every kind it was sent.
// `increment_out_of_range`: whether increments, not only measurements, can be out of range.
void expect_attack_refused(const Target& target, int domain, bool increment_out_of_range) {
  const auto dir = test_dir();
  const int stations = static_cast<int>(target.stations.size());
  const Completed clean =
      run_to_completion(run_args(target, domain, dir / "clean"), dir / "clean.log", 120s);
  ASSERT_EQ(clean.status.code, 0) << clean.output;

  Process attacked(run_args(target, domain, dir / "attacked"), dir / "attacked.log");
  std::vector<std::string> rogue_args = {bin("skyfuse-rogue"),
                                         "--domain",
                                         std::to_string(domain),
                                         "--run-id",
                                         "8086",
                                         "--stations",
                                         std::to_string(stations),
                                         "--victim",
                                         target.stations.front()};
  if (!target.scenario.empty())
    rogue_args.insert(rogue_args.end(), {"--scenario", target.scenario});
  const Completed rogue = run_to_completion(rogue_args, dir / "rogue.log", 120s);
  const std::optional<ExitStatus> status = attacked.wait(120s);
  ASSERT_TRUE(status.has_value()) << attacked.output();
  ASSERT_EQ(status->code, 0) << attacked.output();
  ASSERT_EQ(rogue.status.code, 0) << rogue.output;
  // The rogue reached every reader at every attack step.
  EXPECT_THAT(rogue.output, HasSubstr("sent increment non_finite 3"));
  EXPECT_THAT(rogue.output, HasSubstr("sent measurement out_of_range 3"));
  EXPECT_THAT(rogue.output, HasSubstr("sent measurement wrong_site 3"));

  for (const char* file : {"tracks.csv", "steps.csv", "measurements.csv"}) {
    EXPECT_EQ(read_file(dir / "attacked" / file), read_file(dir / "clean" / file)) << file;
  }

  const auto clean_summary = nlohmann::json::parse(read_file(dir / "clean" / "summary.json"));
  const auto summary = nlohmann::json::parse(read_file(dir / "attacked" / "summary.json"));
  for (const auto& [kind, count] : clean_summary["dropped_by_kind"].items()) {
    EXPECT_EQ(count.get<int>(), 0) << kind;
  }
  // Increments reach the M stations, measurements the center and the harness's recorder.
  const int on_both_topics = kAttackSteps * (stations + 2);
  const auto& by_kind = summary["dropped_by_kind"];
  for (const char* kind :
       {"wrong_run", "future_step", "unknown_station", "non_finite", "not_positive"}) {
    EXPECT_EQ(by_kind[kind].get<int>(), on_both_topics) << kind;
  }
  EXPECT_EQ(by_kind["out_of_range"].get<int>(),
            increment_out_of_range ? on_both_topics : kAttackSteps * 2);
  // The victim's id from 10 m beside its site: the center and the recorder know where it stands.
  EXPECT_EQ(summary["dropped_by_node"]["center"]["wrong_site"].get<int>(), kAttackSteps);
  EXPECT_EQ(summary["dropped_by_node"]["harness"]["wrong_site"].get<int>(), kAttackSteps);
  EXPECT_EQ(by_kind["nis_gate"].get<int>(), 0);
  // The impersonation (a real station's sample for step k + 1 from the rogue's writer) is a
  // duplicate while step k + 1 is open at the receiver; if the rogue woke two rounds late on a
  // loaded machine, the receiver has closed it and the same sample is, rightly, stale. Each
  // node got one of each per attack step, so the two kinds add up exactly either way.
  // (transport::admit's own test pins the order of the checks.)
  std::vector<std::string> nodes = target.stations;
  nodes.insert(nodes.end(), {"center", "harness"});
  for (const std::string& node : nodes) {
    const auto& counts = summary["dropped_by_node"][node];
    EXPECT_EQ(counts["duplicate"].get<int>() + counts["stale_step"].get<int>(), 2 * kAttackSteps)
        << node;
    EXPECT_GE(counts["stale_step"].get<int>(), kAttackSteps) << node;
  }
  EXPECT_GT(by_kind["duplicate"].get<int>(), 0);
  expect_refusals_listed_as_reported(dir / "attacked", summary, 60);
}

TEST(DdsRogue, NothingMalformedIsFusedAndEveryKindIsCounted) {
  expect_attack_refused({"", {"1", "2", "3", "4"}}, 141, false);
}

// Paper 002's receivers run the NCRKF, whose increments need not be positive semi-definite and
// are checked by check_tdoa_increment(): garbage is still refused, kind by kind, and an
// increment with information outside [dx, dy, d_t1] is out of range.
TEST(DdsRogue, NothingMalformedIsFusedByTdoaReceivers) {
  expect_attack_refused({bin("scenarios/paper002.yaml"), {"2", "3", "4"}}, 187, true);
}

}  // namespace
}  // namespace skyfuse::test
