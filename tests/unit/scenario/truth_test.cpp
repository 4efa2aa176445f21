#include "skyfuse/scenario/truth.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace skyfuse {
namespace {

TargetConfig straight_east(double speed) {
  TargetConfig t;
  t.initial_position_m = Vector3(0.0, 0.0, 300.0);
  t.direction = Vector3::UnitX();
  t.speeds_mps = {speed};
  return t;
}

TEST(Truth, FliesStraightAtTheGivenSpeedWithoutManoeuvres) {
  const TruthTrajectory truth = generate_truth(straight_east(50.0), 50.0, 0.02, 100);
  ASSERT_EQ(truth.states.size(), 101U);
  EXPECT_TRUE(truth.position(100).isApprox(Vector3(100.0, 0.0, 300.0), 1e-12));
  EXPECT_EQ(truth.states[37].tail<3>(), Vector3::Zero());
}

TEST(Truth, TurnKeepsTheSpeedAndRotatesTheHeadingByRateTimesDuration) {
  TargetConfig t = straight_east(80.0);
  const double rate = 6.0 * std::numbers::pi / 180.0;
  t.manoeuvres.push_back({Manoeuvre::Kind::kTurn, 1.0, 15.0, Vector3::Zero(), rate});
  const TruthTrajectory truth = generate_truth(t, 80.0, 0.02, 1000);
  const Vector3 v_end = truth.states.back().segment<3>(3);
  EXPECT_NEAR(v_end.norm(), 80.0, 1e-9);
  EXPECT_NEAR(std::atan2(v_end.y(), v_end.x()), rate * 15.0, 1e-9);
  // During the turn the acceleration is centripetal, v * omega in magnitude.
  EXPECT_NEAR(truth.states[400].tail<3>().norm(), 80.0 * rate, 1e-9);
  // The arc is exact: radius v / omega about the turn centre.
  const Vector3 start = truth.position(50);
  const Vector3 centre = start + Vector3(0.0, 80.0 / rate, 0.0);
  EXPECT_NEAR((truth.position(700) - centre).norm(), 80.0 / rate, 1e-6);
}

TEST(Truth, AccelerationChangesVelocityOnlyInsideItsWindow) {
  TargetConfig t = straight_east(30.0);
  t.manoeuvres.push_back({Manoeuvre::Kind::kAccelerate, 1.0, 2.0, Vector3(0.0, 0.0, 0.5), 0.0});
  const TruthTrajectory truth = generate_truth(t, 30.0, 0.02, 250);
  EXPECT_NEAR(truth.states[49](5), 0.0, 1e-12);   // before t = 1 s
  EXPECT_NEAR(truth.states[150](5), 1.0, 1e-12);  // v_z = 0.5 * 2 s
  EXPECT_NEAR(truth.states[250](5), 1.0, 1e-12);
  EXPECT_NEAR(truth.position(250).z(), 300.0 + 0.5 * 0.5 * 4.0 + 1.0 * 2.0, 1e-9);
}

}  // namespace
}  // namespace skyfuse
