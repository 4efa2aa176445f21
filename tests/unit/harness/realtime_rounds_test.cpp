#include "run/realtime_rounds.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace skyfuse::harness {
namespace {

// Stations 2 and 5 and the center; a run of 3 steps.
const std::vector<int> kStations{2, 5};

ReceivedTrack track_fused_from(std::vector<int> contributors, double mean_x = 0.0) {
  // Any state dimension will do: the rounds only move tracks. A 6-entry one, [p; v].
  constexpr int kStateDim = 6;
  ReceivedTrack t;
  t.estimate.mean = Eigen::VectorXd::Zero(kStateDim);
  t.estimate.mean(0) = mean_x;
  t.estimate.covariance = Eigen::MatrixXd::Identity(kStateDim, kStateDim);
  t.contributors = std::move(contributors);
  return t;
}

// Everything step `step` needs: three tracks (all fused from both stations), two measurements.
void deliver_all(RealtimeRounds& rounds, std::uint64_t step) {
  for (int node : {kCenterNodeId, 2, 5}) {
    ASSERT_FALSE(rounds.offer_track(node, step, track_fused_from({2, 5}), 100.0 + node));
  }
  for (int station : kStations) {
    ASSERT_FALSE(rounds.offer_measurement(station, step, Vector3::Constant(station)));
  }
}

TEST(RealtimeRounds, AStepLeavesOnlyWhenEveryTrackAndMeasurementIsIn) {
  RealtimeRounds rounds(kStations, 3);
  std::vector<RoundRecord> done;
  for (int node : {kCenterNodeId, 2, 5}) {
    ASSERT_FALSE(rounds.offer_track(node, 0, track_fused_from({2, 5}), 10.0));
  }
  ASSERT_FALSE(rounds.offer_measurement(2, 0, Vector3::Constant(2.0)));
  EXPECT_EQ(rounds.hand_over(done), 0u);  // station 5's measurement is missing
  EXPECT_TRUE(done.empty());

  ASSERT_FALSE(rounds.offer_measurement(5, 0, Vector3::Constant(5.0)));
  EXPECT_EQ(rounds.hand_over(done), 1u);
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0].step, 0u);
  ASSERT_TRUE(done[0].central && done[0].peers[0] && done[0].peers[1]);
  EXPECT_EQ(*done[0].measurements[1], Vector3::Constant(5.0));
}

// A best-effort measurement lost on the way, a track lost under load: the step leaves with
// what it has once a step kLostAfterSteps later has every track, and not before.
TEST(RealtimeRounds, AStepMissingASampleLeavesOnceALaterStepHasEveryTrack) {
  constexpr std::uint64_t kLater = RealtimeRounds::kLostAfterSteps;
  RealtimeRounds rounds(kStations, kLater + 2);
  std::vector<RoundRecord> done;
  for (int node : {kCenterNodeId, 2, 5}) {
    ASSERT_FALSE(rounds.offer_track(node, 0, track_fused_from({2, 5}), 10.0));
  }
  ASSERT_FALSE(rounds.offer_measurement(2, 0, Vector3::Constant(2.0)));  // 5's never comes
  // Step 1: station 5's track never comes.
  ASSERT_FALSE(rounds.offer_track(kCenterNodeId, 1, track_fused_from({2, 5}), 10.0));
  ASSERT_FALSE(rounds.offer_track(2, 1, track_fused_from({2, 5}), 10.0));
  for (int station : kStations) {
    ASSERT_FALSE(rounds.offer_measurement(station, 1, Vector3::Constant(station)));
  }
  for (std::uint64_t step = 2; step < kLater; ++step) deliver_all(rounds, step);
  EXPECT_EQ(rounds.hand_over(done), 0u) << "no step " << kLater << " steps later yet";

  // Step kLater has every track but one measurement: enough to give up on step 0.
  for (int node : {kCenterNodeId, 2, 5}) {
    ASSERT_FALSE(rounds.offer_track(node, kLater, track_fused_from({2, 5}), 10.0));
  }
  EXPECT_EQ(rounds.hand_over(done), 1u) << "step 1 waits for step " << kLater + 1;
  ASSERT_EQ(done.size(), 1u);
  EXPECT_TRUE(done[0].measurements[0].has_value());
  EXPECT_FALSE(done[0].measurements[1].has_value());
  EXPECT_TRUE(done[0].all_inputs_in_time) << "every node fused both stations";
  EXPECT_EQ(rounds.measurements_lost(), 1u);

  deliver_all(rounds, kLater + 1);
  for (int station : kStations) {
    ASSERT_FALSE(rounds.offer_measurement(station, kLater, Vector3::Constant(station)));
  }
  EXPECT_EQ(rounds.hand_over(done), kLater + 2);
  EXPECT_FALSE(done[1].peers[1].has_value());
  EXPECT_FALSE(done[1].all_inputs_in_time) << "station 5's round is unknown";
  EXPECT_EQ(rounds.tracks_lost(), 1u);
  EXPECT_EQ(rounds.measurements_lost(), 1u);
  EXPECT_EQ(rounds.offer_track(5, 1, track_fused_from({2, 5}), 10.0), DropKind::kStaleStep);
}

TEST(RealtimeRounds, StepsLeaveInOrderWhenALaterOneCompletesFirst) {
  RealtimeRounds rounds(kStations, 3);
  std::vector<RoundRecord> done;
  deliver_all(rounds, 1);
  EXPECT_EQ(rounds.hand_over(done), 0u);  // step 0 is still open
  deliver_all(rounds, 0);
  EXPECT_EQ(rounds.hand_over(done), 2u);
  ASSERT_EQ(done.size(), 2u);
  EXPECT_EQ(done[0].step, 0u);
  EXPECT_EQ(done[1].step, 1u);
}

TEST(RealtimeRounds, RefusesByKind) {
  RealtimeRounds rounds(kStations, 3);
  std::vector<RoundRecord> done;
  EXPECT_EQ(rounds.offer_track(3, 0, track_fused_from({2, 5}), 1.0), DropKind::kUnknownStation);
  EXPECT_EQ(rounds.offer_measurement(kCenterNodeId, 0, Vector3::Zero()), DropKind::kUnknownStation);
  EXPECT_EQ(rounds.offer_track(2, 3, track_fused_from({2, 5}), 1.0), DropKind::kFutureStep);
  EXPECT_EQ(rounds.offer_measurement(5, 3, Vector3::Zero()), DropKind::kFutureStep);

  ASSERT_FALSE(rounds.offer_track(2, 0, track_fused_from({2, 5}, 1.0), 1.0));
  EXPECT_EQ(rounds.offer_track(2, 0, track_fused_from({2, 5}, 2.0), 1.0), DropKind::kDuplicate);
  ASSERT_FALSE(rounds.offer_measurement(5, 0, Vector3::Zero()));
  EXPECT_EQ(rounds.offer_measurement(5, 0, Vector3::Ones()), DropKind::kDuplicate);

  deliver_all(rounds, 1);  // step 1 waits for step 0
  EXPECT_EQ(rounds.hand_over(done), 0u);
  ASSERT_FALSE(rounds.offer_track(kCenterNodeId, 0, track_fused_from({2, 5}), 1.0));
  ASSERT_FALSE(rounds.offer_track(5, 0, track_fused_from({2, 5}), 1.0));
  ASSERT_FALSE(rounds.offer_measurement(2, 0, Vector3::Zero()));
  ASSERT_EQ(rounds.hand_over(done), 2u);
  // The first of the two tracks was kept, not the duplicate.
  EXPECT_EQ(done[0].peers[0]->estimate.mean(0), 1.0);
  EXPECT_EQ(*done[0].measurements[1], Vector3::Zero());
  EXPECT_EQ(rounds.check_track(2, 1), DropKind::kStaleStep);
  EXPECT_EQ(rounds.check_measurement(5, 0), DropKind::kStaleStep);
  EXPECT_FALSE(rounds.check_track(2, 2));
}

TEST(RealtimeRounds, LatencyIsTheOldestTrackAndAShortFusionIsNotInTime) {
  RealtimeRounds rounds(kStations, 1);
  std::vector<RoundRecord> done;
  ASSERT_FALSE(rounds.offer_track(kCenterNodeId, 0, track_fused_from({2, 5}), 1500.0));
  ASSERT_FALSE(rounds.offer_track(2, 0, track_fused_from({2, 5}), 2500.0));
  ASSERT_FALSE(rounds.offer_track(5, 0, track_fused_from({5}), 700.0));  // missed station 2
  ASSERT_FALSE(rounds.offer_measurement(2, 0, Vector3::Zero()));
  ASSERT_FALSE(rounds.offer_measurement(5, 0, Vector3::Zero()));
  ASSERT_EQ(rounds.hand_over(done), 1u);
  EXPECT_EQ(done[0].latency, std::chrono::microseconds(2500));
  EXPECT_EQ(done[0].track_age_us, (std::vector<double>{1500.0, 2500.0, 700.0}));
  EXPECT_FALSE(done[0].all_inputs_in_time);

  RealtimeRounds all_in(kStations, 1);
  deliver_all(all_in, 0);
  std::vector<RoundRecord> complete;
  ASSERT_EQ(all_in.hand_over(complete), 1u);
  EXPECT_TRUE(complete[0].all_inputs_in_time);
}

}  // namespace
}  // namespace skyfuse::harness
