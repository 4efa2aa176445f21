// A track's height bound by the band its 2-D radars assume (picture/height_bound.hpp).
#include "skyfuse/picture/height_bound.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "skyfuse/models/range_azimuth.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/tracking/imm_modes.hpp"

namespace skyfuse {
namespace {

constexpr int N = 6;
const HeightBand kBand{120.0, 450.0};  // variance 9 075 m²

GaussianState<N> spread_in_height(double height_variance) {
  GaussianState<N> state;
  state.mean << 1000.0, -2000.0, 900.0, 20.0, -5.0, 3.0;
  state.covariance = Covariance<N>::Identity() * 25.0;
  state.covariance(2, 2) = height_variance;
  state.covariance(2, 5) = state.covariance(5, 2) = 0.5 * std::sqrt(height_variance * 25.0);
  state.covariance(0, 2) = state.covariance(2, 0) = 0.2 * std::sqrt(height_variance * 25.0);
  return state;
}

// P = 4V: the pseudo-measurement leaves V, moves the height 3/4 of the way to the band's middle
// (gain (P - V)/P), and the entries correlated with it by their correlation.
TEST(HeightBound, AHeightLessKnownThanTheBandIsBoundToItsVariance) {
  const double v = kBand.variance_m2();
  GaussianState<N> state = spread_in_height(4.0 * v);
  const GaussianState<N> before = state;
  ASSERT_TRUE(bound_height(state, kBand));
  EXPECT_NEAR(state.covariance(2, 2), v, 1e-9 * v);
  EXPECT_NEAR(state.mean(2), 900.0 + 0.75 * (kBand.middle_m() - 900.0), 1e-9);
  const double moved = 0.75 * (kBand.middle_m() - 900.0) / (4.0 * v);
  EXPECT_NEAR(state.mean(5), before.mean(5) + before.covariance(5, 2) * moved, 1e-12);
  EXPECT_NEAR(state.mean(0), before.mean(0) + before.covariance(0, 2) * moved, 1e-12);
  EXPECT_EQ(state.mean(1), before.mean(1))
      << "an entry uncorrelated with the height keeps its value";
  EXPECT_EQ(state.covariance, state.covariance.transpose());
  EXPECT_EQ(Eigen::LLT<Covariance<N>>(state.covariance).info(), Eigen::Success);
  // Bound again: nothing left to take.
  const GaussianState<N> once = state;
  EXPECT_FALSE(bound_height(state, kBand));
  EXPECT_EQ(state.mean, once.mean);
}

TEST(HeightBound, AHeightSomethingMeasuresIsLeftBitForBit) {
  GaussianState<N> state = spread_in_height(0.5 * kBand.variance_m2());
  const GaussianState<N> before = state;
  EXPECT_FALSE(bound_height(state, kBand));
  EXPECT_EQ(state.mean, before.mean);
  EXPECT_EQ(state.covariance, before.covariance);
}

TEST(HeightBound, TheBandIsTheTwoDimensionalRadarsAndNoneWithout) {
  Covariance<2> noise2 = Covariance<2>::Identity();
  Covariance<3> noise3 = Covariance<3>::Identity();
  const std::vector<KnownStation<N>> mixed = {
      {1, RangeAzimuth<N>(Vector3::Zero(), HeightBand{100.0, 300.0}), noise2, 1.0, {}},
      {2, RangeAzimuthElevation<N>(Vector3::Zero()), noise3, 1.0, {}},
      {3, RangeAzimuth<N>(Vector3::Zero(), HeightBand{200.0, 500.0}), noise2, 1.0, {}}};
  const auto band = assumed_height_band(std::span<const KnownStation<N>>(mixed));
  ASSERT_TRUE(band.has_value());
  EXPECT_EQ(band->low_m, 100.0);
  EXPECT_EQ(band->high_m, 500.0);
  const std::vector<KnownStation<N>> three_d = {mixed[1]};
  EXPECT_FALSE(assumed_height_band(std::span<const KnownStation<N>>(three_d)).has_value());
}

// An IMM track: every mode bound alike, the mode probabilities kept.
TEST(HeightBound, EveryModeOfAnImmTrackIsBoundAndItsProbabilitiesKept) {
  using Tracks = PeerImmTracks<DefaultImmModes>;
  constexpr int K = KinematicState::kDim;
  const Scenario scenario =
      load_scenario_file(std::string(SKYFUSE_SOURCE_DIR) + "/scenarios/paper000-imm.yaml");
  const Tracks tracks(scenario);
  GaussianState<K> start;
  start.mean = Vector<K>::Zero();
  start.mean(2) = 900.0;
  start.covariance = Covariance<K>::Identity() * 25.0;
  start.covariance(2, 2) = 4.0 * kBand.variance_m2();
  auto state = tracks.start(start);
  const auto probabilities = state.filter().mode_probabilities();
  ASSERT_TRUE(bound_height(state, kBand));
  const auto expect_bound = [&](const auto& mode) {
    EXPECT_NEAR(mode.covariance(2, 2), kBand.variance_m2(), 1e-9 * kBand.variance_m2());
    EXPECT_NEAR(mode.mean(2), 900.0 + 0.75 * (kBand.middle_m() - 900.0), 1e-9);
  };
  std::apply([&](const auto&... mode) { (expect_bound(mode), ...); }, state.filter().mode_states());
  EXPECT_EQ(state.filter().mode_probabilities(), probabilities);
}

}  // namespace
}  // namespace skyfuse
