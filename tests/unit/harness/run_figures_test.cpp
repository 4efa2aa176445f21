#include "run/run_figures.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace skyfuse::harness {
namespace {

using ::testing::HasSubstr;

// 64 stations at 50 Hz on 1.5 ms of CPU per station-round: 4.8 cores' worth.
RunFigures busy_run() {
  RunFigures s;
  s.stations = 64;
  s.steps = 400;
  s.steps_planned = 1000;
  s.cpu_ms_per_station_round = 1.5;
  return s;
}

TEST(HostVerdict, ALockStepRunSaysNothing) {
  EXPECT_EQ(host_verdict(busy_run(), RealtimeLoad{0.0, 0.5, 400, 0.0}, 0.02, "cpu", 2), "");
}

TEST(HostVerdict, ARealTimeRunWithNearlyEveryRoundInTimeSaysNothing) {
  EXPECT_EQ(host_verdict(busy_run(), RealtimeLoad{15.0, 0.995, 400, 0.0}, 0.02, "cpu", 2), "");
}

// A run of either kind that kept its rounds only in part: what it used and what that needs.
TEST(HostVerdict, ARealTimeRunKeptInPartSaysWhatItCost) {
  const std::string verdict =
      host_verdict(busy_run(), RealtimeLoad{15.0, 0.9, 400, 0.0}, 0.02, "Some CPU", 2);
  EXPECT_THAT(verdict, HasSubstr("this host (Some CPU, 2 cores) carried 64 stations at 50 Hz "
                                 "with a 15 ms deadline only in part: 90.0 % of the rounds"));
  EXPECT_THAT(verdict, HasSubstr("1.50 ms of CPU per station-round, 4.8 cores' worth"));
}

TEST(HostVerdict, ARunThatFellBehindSaysHowFar) {
  RunFigures s = busy_run();
  s.stop_cause = StopCause::kFellBehind;
  const std::string verdict =
      host_verdict(s, RealtimeLoad{15.0, 0.999, 380, 2.5}, 0.02, "Some CPU", 2);
  EXPECT_THAT(verdict, HasSubstr("could not carry 64 stations at 50 Hz with a 15 ms deadline: "
                                 "380 of 1000 steps complete (400 recorded), 2.5 s behind"));
}

TEST(RunFigures, TakeCopiesWhatTheHouseMeasuredAndWhyTheRoundsStopped) {
  ProcessMeasures measured;
  measured.discovery = "peers";
  measured.discovery_s = 1.25;
  measured.settle_s = 0.5;
  measured.settled_quiet = false;
  measured.datagrams_per_round = 300.0;
  measured.cpu_ms_per_station_round = 0.75;
  measured.node_peak_resident_mib = 42.0;
  measured.node_exits = {{"station 1", "exit 0"}};
  measured.stopped = RunAborted("interrupted by signal 2", StopCause::kInterrupted);
  RunFigures s;
  s.take(measured);
  EXPECT_EQ(s.discovery, "peers");
  EXPECT_EQ(s.discovery_s, 1.25);
  EXPECT_EQ(s.settle_s, 0.5);
  EXPECT_FALSE(s.settled_quiet);
  EXPECT_EQ(s.datagrams_per_round, 300.0);
  EXPECT_EQ(s.cpu_ms_per_station_round, 0.75);
  EXPECT_EQ(s.node_peak_resident_mib, 42.0);
  EXPECT_EQ(s.node_exits.at("station 1"), "exit 0");
  EXPECT_EQ(s.stop_cause, StopCause::kInterrupted);
  EXPECT_EQ(s.end_detail, "interrupted by signal 2");
}

}  // namespace
}  // namespace skyfuse::harness
