#include "skyfuse/experiments/paper003.hpp"

#include <gtest/gtest.h>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/position_velocity.hpp"

namespace skyfuse {
namespace {

TEST(Paper003, TheSteadyStateIsAFixedPointOfTheRiccatiRecursion) {
  const Paper003Setup setup;
  const Paper003Result r = run_paper003(setup);
  const ConstantVelocity3D model(setup.time_step_s, {5.0, 3.0});
  GaussianState<6> state{Vector<6>::Zero(), r.steady_state_posterior};
  predict(state, model);
  Vector<6> noise;
  noise << 9.0, 9.0, 9.0, 4.0, 4.0, 4.0;
  update(state, PositionVelocity<6>(), Vector<6>::Zero(), Covariance<6>(noise.asDiagonal()));
  EXPECT_LE((state.covariance - r.steady_state_posterior).cwiseAbs().maxCoeff(), 1e-9);
  // Each axis is filtered alike, and the GPS makes it better than either source alone.
  const Vector<6> d = r.steady_state_posterior.diagonal();
  EXPECT_NEAR(d(0), d(2), 1e-9);
  EXPECT_LT(d(0), 9.0);
}

TEST(Paper003, MonteCarloMseSettlesAtTheSteadyState) {
  Paper003Setup setup;
  setup.runs = 400;
  const Paper003Result r = run_paper003(setup);
  const double steady = r.steady_state_posterior.diagonal().head<3>().sum();
  double sum = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < r.time_s.size(); ++k) {
    if (r.time_s[k] <= 4.0) continue;
    sum += r.mse_position[k].sum();
    ++n;
  }
  EXPECT_NEAR(sum / n / steady, 1.0, 0.05);
  // The first step still carries the prior's 100 m error in height.
  EXPECT_GT(r.mse_position.front().z(), 100.0);
}

TEST(Paper003, TheSameSeedGivesTheSameNumbers) {
  Paper003Setup setup;
  setup.runs = 5;
  const Paper003Result a = run_paper003(setup);
  const Paper003Result b = run_paper003(setup);
  setup.seed += 1;
  const Paper003Result c = run_paper003(setup);
  ASSERT_EQ(a.mse_position.size(), 100U);
  EXPECT_EQ(a.mse_position.back(), b.mse_position.back());
  EXPECT_NE(a.mse_position.back(), c.mse_position.back());
  EXPECT_DOUBLE_EQ(a.time_s.front(), 0.5);
  EXPECT_DOUBLE_EQ(a.time_s.back(), 50.0);
}

TEST(Paper003, RefusesASetupWithoutRuns) {
  Paper003Setup setup;
  setup.runs = 0;
  EXPECT_THROW(run_paper003(setup), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse
