// Paper 001's data: the path generator's kinematics, the split by path, and the windows the
// networks learn from.

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "skyfuse/experiments/paper001/dataset.hpp"
#include "skyfuse/experiments/paper001/filter_tracks.hpp"

namespace skyfuse::paper001 {
namespace {

TEST(Paper001Paths, AreAPureFunctionOfSeedAndIndex) {
  const PathSetup setup;
  const ManoeuvringPath a = generate_path(setup, 7, 42);
  const ManoeuvringPath b = generate_path(setup, 7, 42);
  const ManoeuvringPath other = generate_path(setup, 7, 43);
  ASSERT_EQ(a.truth.size(), static_cast<std::size_t>(setup.steps));
  for (std::size_t k = 0; k < a.truth.size(); ++k) {
    ASSERT_EQ(a.truth[k], b.truth[k]);
    ASSERT_EQ(a.measurements[k], b.measurements[k]);
  }
  EXPECT_NE(a.truth.back(), other.truth.back());
}

TEST(Paper001Paths, FollowEquation10WithinTheSpeedLimits) {
  const PathSetup setup;
  const double dt = setup.time_step_s;
  for (std::uint64_t index = 0; index < 50; ++index) {
    const ManoeuvringPath path = generate_path(setup, 1, index);
    EXPECT_EQ(path.truth[0].head<2>(), Vector<2>::Zero());
    EXPECT_EQ(path.truth[0](4), 0.0);
    for (std::size_t k = 1; k < path.truth.size(); ++k) {
      const Vector<5>& before = path.truth[k - 1];
      const Vector<5>& now = path.truth[k];
      ASSERT_NEAR(now(0), before(0) + before(3) * dt * std::cos(before(2)), 1e-9);
      ASSERT_NEAR(now(1), before(1) + before(3) * dt * std::sin(before(2)), 1e-9);
      ASSERT_GE(now(3), 0.0);
      ASSERT_LE(now(3), setup.max_speed_mps);
      // Acceleration is at most 5 m/s^2 except while braking at 20.
      ASSERT_LE(std::abs(now(3) - before(3)), 20.0 * dt + 1e-12);
    }
  }
}

TEST(Paper001Paths, MeasurementNoiseHasTheStatedSpread) {
  const PathSetup setup;
  double sum = 0.0;
  double squares = 0.0;
  int n = 0;
  for (std::uint64_t index = 0; index < 40; ++index) {
    const ManoeuvringPath path = generate_path(setup, 3, index);
    for (std::size_t k = 0; k < path.truth.size(); ++k) {
      const Vector<2> e = path.measurements[k] - path.truth[k].head<2>();
      sum += e.sum();
      squares += e.squaredNorm();
      n += 2;
    }
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 0.0, 4.0 * 3.0 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(squares / n), 3.0, 0.05);
}

TEST(Paper001Paths, ATenthBrakeSuddenlyBeforeAManoeuvre) {
  const PathSetup setup;
  int braking = 0;
  constexpr int kPaths = 2000;
  for (std::uint64_t index = 0; index < kPaths; ++index) {
    const ManoeuvringPath path = generate_path(setup, 5, index);
    bool braked = false;
    for (std::size_t k = 1; k < path.truth.size(); ++k) {
      const double change = path.truth[k](3) - path.truth[k - 1](3);
      braked = braked || change < -5.0 * setup.time_step_s - 1e-9;
    }
    EXPECT_EQ(braked && !path.has_sudden_deceleration, false) << "path " << index;
    braking += path.has_sudden_deceleration ? 1 : 0;
  }
  // Binomial(2000, 0.1): standard deviation 13.4.
  EXPECT_NEAR(braking, 200, 55);
}

TEST(Paper001Data, SplitsSevenTwoOneByPath) {
  const DataSetup setup;
  const std::vector<int> train = paths_in(setup, Split::kTrain);
  const std::vector<int> validation = paths_in(setup, Split::kValidation);
  const std::vector<int> test = paths_in(setup, Split::kTest);
  EXPECT_EQ(train.size(), 7000u);
  EXPECT_EQ(validation.size(), 2000u);
  EXPECT_EQ(test.size(), 1000u);
  std::set<int> all(train.begin(), train.end());
  all.insert(validation.begin(), validation.end());
  all.insert(test.begin(), test.end());
  EXPECT_EQ(all.size(), 10000u);
  EXPECT_THROW(split_of(setup, 10000), std::out_of_range);
}

TEST(Paper001Data, WindowsCarryTheCvkfAndTheMeasurementsAndTheirTargets) {
  DataSetup setup;
  setup.paths = 10;
  const TrackedPath tracked = track_path(setup, 9);
  const Matrix<kWindowSteps, kWindowFeatures> w =
      window_features(tracked, 20, WindowFrame::kAbsolute);
  // Row 0 is step 7, row 13 step 20.
  EXPECT_EQ(w.row(13).head<4>().transpose(), tracked.cvkf[20]);
  EXPECT_EQ(w.row(0).tail<2>().transpose(), tracked.path.measurements[7]);
  const Vector<2> error = window_target(tracked, 20, Network::kErrorCompensation);
  EXPECT_EQ(error, Vector<2>(tracked.path.truth[20](0) - tracked.cvkf[20](0),
                             tracked.path.truth[20](1) - tracked.cvkf[20](2)));
  EXPECT_EQ(window_target(tracked, 20, Network::kStateEstimation),
            tracked.path.truth[20].head<2>());
  EXPECT_THROW(window_features(tracked, 12, WindowFrame::kAbsolute), std::out_of_range);

  // One test path, stride 3: (L - 14) / 3 + 1 windows, in order.
  const Windows windows =
      make_windows(setup, Split::kTest, Network::kErrorCompensation, 3, WindowFrame::kAbsolute);
  const int steps = setup.path.steps;
  EXPECT_EQ(windows.count(), static_cast<std::size_t>((steps - kWindowSteps) / 3 + 1));
  EXPECT_EQ(windows.inputs.size(), windows.count() * kWindowSteps * kWindowFeatures);
  EXPECT_FLOAT_EQ(windows.targets[2],
                  static_cast<float>(window_target(tracked, 16, Network::kErrorCompensation)(0)));
  EXPECT_FLOAT_EQ(windows.inputs[kWindowSteps * kWindowFeatures + 4],
                  static_cast<float>(tracked.path.measurements[3](0)));
}

// Relative to the CVKF position at the window's last step: the positions shift, the
// velocities stay, and the whole window is the same wherever the path lies.
TEST(Paper001Data, RelativeWindowsAreTheAbsoluteOnesMovedToTheLastEstimate) {
  DataSetup setup;
  setup.paths = 10;
  TrackedPath tracked = track_path(setup, 9);
  const auto absolute = window_features(tracked, 40, WindowFrame::kAbsolute);
  const auto relative = window_features(tracked, 40, WindowFrame::kRelative);
  const double x0 = tracked.cvkf[40](0);
  const double y0 = tracked.cvkf[40](2);
  EXPECT_EQ(relative(13, 0), 0.0);
  EXPECT_EQ(relative(13, 2), 0.0);
  for (int row = 0; row < kWindowSteps; ++row) {
    EXPECT_DOUBLE_EQ(relative(row, 0), absolute(row, 0) - x0);
    EXPECT_EQ(relative(row, 1), absolute(row, 1));
    EXPECT_DOUBLE_EQ(relative(row, 2), absolute(row, 2) - y0);
    EXPECT_EQ(relative(row, 3), absolute(row, 3));
    EXPECT_DOUBLE_EQ(relative(row, 4), absolute(row, 4) - x0);
    EXPECT_DOUBLE_EQ(relative(row, 5), absolute(row, 5) - y0);
  }
  // The same path 1 km away (every position moved by a power of two, so exactly).
  for (Vector<4>& x : tracked.cvkf) x(0) += 1024.0, x(2) -= 1024.0;
  for (Vector<2>& z : tracked.path.measurements) z += Vector<2>(1024.0, -1024.0);
  EXPECT_NE(window_features(tracked, 40, WindowFrame::kAbsolute), absolute);
  EXPECT_TRUE(window_features(tracked, 40, WindowFrame::kRelative).isApprox(relative, 1e-12));

  EXPECT_EQ(window_frame_named("relative"), WindowFrame::kRelative);
  EXPECT_STREQ(name_of(window_frame_named("absolute")), "absolute");
  EXPECT_THROW(window_frame_named("polar"), std::invalid_argument);
}

TEST(Paper001Data, RmseOfTheTruthIsZeroAndOfAnOffsetTrackItsOffset) {
  DataSetup setup;
  setup.paths = 10;
  const TrackedPath tracked = track_path(setup, 0);
  PositionTrack truth;
  PositionTrack offset;
  for (const Vector<5>& x : tracked.path.truth) {
    truth.emplace_back(x.head<2>());
    offset.emplace_back(x.head<2>() + Vector<2>(3.0, 4.0));
  }
  EXPECT_EQ(path_rmse(tracked, truth), 0.0);
  EXPECT_NEAR(path_rmse(tracked, offset), 5.0, 1e-12);
  // Per axis: the mean of 3^2 and 4^2, i.e. 12.5 m^2.
  EXPECT_NEAR(per_axis_rmse(tracked, offset), std::sqrt(12.5), 1e-12);
  truth.pop_back();
  EXPECT_THROW(path_rmse(tracked, truth), std::invalid_argument);
}

TEST(Paper001Filters, ImmBeatsTheCvkfOnManoeuvringPaths) {
  DataSetup setup;
  setup.paths = 20;
  double cvkf = 0.0;
  double imm = 0.0;
  for (int i = 0; i < setup.paths; ++i) {
    const TrackedPath tracked = track_path(setup, i);
    cvkf += path_rmse(tracked, cvkf_track(tracked));
    imm += path_rmse(tracked, imm_track(setup, tracked));
  }
  EXPECT_LT(imm, 0.8 * cvkf);
}

}  // namespace
}  // namespace skyfuse::paper001
