// A rogue process inside the run's domain publishes every malformed kind on the real increment
// and measurement topics. Nothing it sends may be fused - the tracks equal those of the same run
// without it, bit for bit - and every receiver counts each kind it was sent.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "integration/run_fixture.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

constexpr int kStations = 4;
constexpr int kAttackSteps = 3;  // the rogue's default steps 5, 10 and 15 of the run's 60

std::vector<std::string> run_args(int domain, const std::filesystem::path& out) {
  return {bin("skyfuse"), "run",  "--stations", std::to_string(kStations), "--steps", "60",
          "--run-id",     "8086", "--domain",   std::to_string(domain),    "--out",   out.string()};
}

TEST(DdsRogue, NothingMalformedIsFusedAndEveryKindIsCounted) {
  const auto dir = test_dir();
  const int domain = 141;
  const Completed clean =
      run_to_completion(run_args(domain, dir / "clean"), dir / "clean.log", 120s);
  ASSERT_EQ(clean.status.code, 0) << clean.output;

  Process attacked(run_args(domain, dir / "attacked"), dir / "attacked.log");
  const Completed rogue =
      run_to_completion({bin("skyfuse-rogue"), "--domain", std::to_string(domain), "--run-id",
                         "8086", "--stations", std::to_string(kStations)},
                        dir / "rogue.log", 120s);
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
  const int on_both_topics = kAttackSteps * (kStations + 2);
  const auto& by_kind = summary["dropped_by_kind"];
  for (const char* kind :
       {"wrong_run", "future_step", "unknown_station", "non_finite", "not_positive"}) {
    EXPECT_EQ(by_kind[kind].get<int>(), on_both_topics) << kind;
  }
  EXPECT_EQ(by_kind["out_of_range"].get<int>(), kAttackSteps * 2);  // measurements only
  // The victim's id from 10 m beside its site: the center and the recorder know where it stands.
  EXPECT_EQ(summary["dropped_by_node"]["center"]["wrong_site"].get<int>(), kAttackSteps);
  EXPECT_EQ(summary["dropped_by_node"]["harness"]["wrong_site"].get<int>(), kAttackSteps);
  EXPECT_EQ(by_kind["nis_gate"].get<int>(), 0);
  // The impersonation (a real station's sample for step k + 1 from the rogue's writer) is a
  // duplicate while step k + 1 is open at the receiver; if the rogue woke two rounds late on a
  // loaded machine, the receiver has closed it and the same sample is, rightly, stale. Each
  // node got one of each per attack step, so the two kinds add up exactly either way.
  // (transport::admit's own test pins the order of the checks.)
  for (const char* node : {"1", "2", "3", "4", "center", "harness"}) {
    const auto& counts = summary["dropped_by_node"][node];
    EXPECT_EQ(counts["duplicate"].get<int>() + counts["stale_step"].get<int>(), 2 * kAttackSteps)
        << node;
    EXPECT_GE(counts["stale_step"].get<int>(), kAttackSteps) << node;
  }
  EXPECT_GT(by_kind["duplicate"].get<int>(), 0);
}

}  // namespace
}  // namespace skyfuse::test
