#include "skyfuse/picture/associators/jpda.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "unit/picture/associators/association_fixture.hpp"

namespace skyfuse {
namespace {

using testing::decide;
using testing::detection_at;
using testing::kGate;
using testing::scan_of;
using testing::track_at;

// Three tracks close enough that every one of four detections gates with each: one cluster,
// 73 joint events.
std::vector<GaussianState<6>> three_tracks() {
  return {track_at({0, 0, 100}), track_at({3, 0, 100}), track_at({1.5, 2.5, 100})};
}
Scan four_detections() {
  return scan_of({detection_at({0.5, 0.3, 100}), detection_at({2.2, 0.4, 100}),
                  detection_at({1.6, 1.8, 100}), detection_at({4.0, 1.0, 100})});
}

// The same, behind a cluster of its own that comes first: a lone track with one detection.
std::vector<GaussianState<6>> lone_and_three_tracks() {
  std::vector<GaussianState<6>> tracks = {track_at({500, 0, 100})};
  for (const auto& t : three_tracks()) tracks.push_back(t);
  return tracks;
}
Scan lone_and_four_detections() {
  Scan scan = four_detections();
  scan.detections.push_back(detection_at({500.5, 0.2, 100}));
  return scan;
}

// beta[t][j] (j = detections: "none") by enumerating every map of tracks to detections or none
// that uses no detection twice and only gated pairs, each event weighed by
// prod P_D N(nu; 0, S) / lambda * prod (1 - P_D P_G), with N computed here by Eigen's
// determinant and inverse.
std::vector<std::vector<double>> brute_force(const std::vector<GaussianState<6>>& tracks,
                                             const Scan& scan, const DetectionPrior& prior) {
  const std::size_t n = tracks.size();
  const std::size_t m = scan.detections.size();
  std::vector<std::vector<double>> g(n, std::vector<double>(m, 0.0));  // 0: not gated
  const testing::PvSensor sensor;
  for (std::size_t t = 0; t < n; ++t) {
    const Eigen::Matrix<double, 6, 6> h = sensor.jacobian(tracks[t].mean);
    const Eigen::Matrix<double, 6, 6> s =
        h * tracks[t].covariance * h.transpose() + fixed_noise<6>(scan.noise);
    for (std::size_t j = 0; j < m; ++j) {
      const Vector<6> nu = fixed_detection<6>(scan.detections[j]) - sensor.predict(tracks[t].mean);
      const double d2 = nu.dot(s.inverse() * nu);
      if (d2 > kGate) continue;
      g[t][j] =
          std::exp(-0.5 * d2) / std::sqrt(std::pow(2.0 * std::numbers::pi, 6) * s.determinant());
    }
  }
  std::vector<std::vector<double>> beta(n, std::vector<double>(m + 1, 0.0));
  std::vector<int> choice(n, -1);
  std::vector<char> used(m, 0);
  double total = 0.0;
  std::function<void(std::size_t)> visit = [&](std::size_t t) {
    if (t == n) {
      double w = 1.0;
      for (std::size_t i = 0; i < n; ++i) {
        w *= choice[i] < 0 ? 1.0 - prior.detection_probability * prior.gate_probability
                           : prior.detection_probability *
                                 g[i][static_cast<std::size_t>(choice[i])] / prior.clutter_density;
      }
      total += w;
      for (std::size_t i = 0; i < n; ++i) {
        beta[i][choice[i] < 0 ? m : static_cast<std::size_t>(choice[i])] += w;
      }
      return;
    }
    choice[t] = -1;
    visit(t + 1);
    for (std::size_t j = 0; j < m; ++j) {
      if (used[j] || g[t][j] == 0.0) continue;
      used[j] = 1;
      choice[t] = static_cast<int>(j);
      visit(t + 1);
      used[j] = 0;
    }
    choice[t] = -1;
  };
  visit(0);
  for (auto& row : beta) {
    for (double& b : row) b /= total;
  }
  return beta;
}

TEST(JpdaAssociator, ProbabilitiesOfASmallClusterAreTheEnumeratedJointEvents) {
  const DetectionPrior prior{
      .detection_probability = 0.9, .gate_probability = 0.9999, .clutter_density = 1e-5};
  const auto tracks = lone_and_three_tracks();
  const Scan scan = lone_and_four_detections();
  const ScanAssociation a = decide("jpda", tracks, scan, 4096, prior);
  const auto expected = brute_force(tracks, scan, prior);

  ASSERT_EQ(a.pairs.size(), 13U);  // every pair of a cluster gates, none has probability 0
  EXPECT_EQ(a.largest_cluster, 3U);
  EXPECT_EQ(a.fallback_clusters, 0U);
  EXPECT_TRUE(a.unassociated.empty());  // every detection may be a track's
  std::vector<double> missed(tracks.size(), 1.0);
  for (const WeightedPair& p : a.pairs) {
    const auto t = static_cast<std::size_t>(p.track);
    EXPECT_NEAR(p.weight, expected[t][p.detection], 1e-12)
        << "track " << p.track << ", detection " << p.detection;
    missed[t] -= p.weight;
  }
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    EXPECT_NEAR(missed[t], expected[t][scan.detections.size()], 1e-12) << "track " << t;
  }
  // The pairs ascend by track, then detection, as the report and the wire take them.
  for (std::size_t i = 1; i < a.pairs.size(); ++i) {
    EXPECT_LT(std::pair(a.pairs[i - 1].track, a.pairs[i - 1].detection),
              std::pair(a.pairs[i].track, a.pairs[i].detection));
  }
}

TEST(JpdaAssociator, AnIsolatedTrackAndDetectionFollowTheSinglePdaFormula) {
  const DetectionPrior prior{
      .detection_probability = 0.8, .gate_probability = 0.9999, .clutter_density = 1e-4};
  const std::vector<GaussianState<6>> tracks = {track_at({0, 0, 100})};
  const ScanAssociation a =
      decide("jpda", tracks, scan_of({detection_at({1, 0, 100}), detection_at({900, 0, 100})}),
             4096, prior);
  ASSERT_EQ(a.pairs.size(), 1U);
  // S = 2 I: N(nu; 0, S) = exp(-|nu|^2 / 4) / (4 pi)^3.
  const double g = 0.8 * std::exp(-0.25) / std::pow(4.0 * std::numbers::pi, 3) / 1e-4;
  EXPECT_NEAR(a.pairs[0].weight, g / (g + 1.0 - 0.8 * 0.9999), 1e-14);
  EXPECT_EQ(a.unassociated, (std::vector<std::uint32_t>{1}));  // gated with no track
}

TEST(JpdaAssociator, AClusterWithTooManyEventsIsDecidedByGnnAndCounted) {
  AssociationConfig config;
  config.associator = "jpda";
  config.jpda_max_events = 10;  // the cluster's bound is 5^3 = 125
  AssociationWork work;
  const auto tracks = three_tracks();
  const Scan scan = four_detections();
  hypothesise(std::span<const GaussianState<6>>(tracks), testing::PvSensor(), scan, kGate, 4096,
              true, IdentityMask{}, work.hypothesiser, work.hypotheses);
  ScanAssociation jpda;
  associate_jpda(work.hypotheses, DetectionPrior{}, config, work, jpda);
  const ScanAssociation gnn = decide("gnn", tracks, scan);
  EXPECT_EQ(jpda.fallback_clusters, 1U);
  ASSERT_EQ(jpda.pairs.size(), gnn.pairs.size());
  for (std::size_t i = 0; i < gnn.pairs.size(); ++i) {
    EXPECT_EQ(jpda.pairs[i].track, gnn.pairs[i].track);
    EXPECT_EQ(jpda.pairs[i].detection, gnn.pairs[i].detection);
    EXPECT_EQ(jpda.pairs[i].weight, 1.0);
  }
  EXPECT_EQ(jpda.unassociated, gnn.unassociated);
}

}  // namespace
}  // namespace skyfuse
