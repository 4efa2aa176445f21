#include "skyfuse/picture/hypothesiser.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <vector>

#include "unit/picture/associators/association_fixture.hpp"

namespace skyfuse {
namespace {

using testing::detection_at;
using testing::kGate;
using testing::scan_of;
using testing::track_at;

TEST(Hypothesiser, EachGatedPairCarriesItsNisAndGaussianLogDensity) {
  std::vector<GaussianState<6>> tracks = {track_at({0, 0, 100}), track_at({50, 0, 100})};
  tracks[1].covariance.diagonal() << 4.0, 1.0, 2.0, 1.0, 1.0, 3.0;
  const Scan scan = scan_of(
      {detection_at({51, 1, 99}), detection_at({0.5, -0.5, 100.5}), detection_at({25, 0, 100})});
  HypothesiserWork work;
  Hypotheses h;
  hypothesise(std::span<const GaussianState<6>>(tracks), testing::PvSensor(), scan, kGate, 4096,
              true, IdentityMask{}, work, h);
  EXPECT_EQ(h.tracks, 2U);
  EXPECT_EQ(h.detections, 3U);
  EXPECT_EQ(h.gate, kGate);
  ASSERT_EQ(h.pairs.size(), 2U);  // detection 2 lies between the tracks, in neither's gate
  for (const Hypothesis& pair : h.pairs) {
    const auto& prior = tracks[static_cast<std::size_t>(pair.track)];
    const Eigen::Matrix<double, 6, 6> s = prior.covariance + fixed_noise<6>(scan.noise);
    const Vector<6> nu =
        fixed_detection<6>(scan.detections[static_cast<std::size_t>(pair.detection)]) - prior.mean;
    const double nis = nu.dot(s.inverse() * nu);
    EXPECT_NEAR(pair.nis, nis, 1e-12);
    EXPECT_NEAR(pair.log_density,
                -0.5 * nis - 0.5 * std::log(std::pow(2.0 * std::numbers::pi, 6) * s.determinant()),
                1e-12);
  }
  EXPECT_EQ(h.pairs[0].track, 0);
  EXPECT_EQ(h.pairs[0].detection, 1);
  EXPECT_EQ(h.pairs[1].track, 1);
  EXPECT_EQ(h.pairs[1].detection, 0);
}

}  // namespace
}  // namespace skyfuse
