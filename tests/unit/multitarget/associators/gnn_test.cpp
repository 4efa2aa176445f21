#include "skyfuse/multitarget/scan_assignment.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "skyfuse/metrics/chi_square.hpp"
#include "skyfuse/models/position_velocity.hpp"

namespace skyfuse {
namespace {

using Sensor = PositionVelocity<6>;

GaussianState<6> track_at(const Vector3& position) {
  GaussianState<6> prior;
  prior.mean.head<3>() = position;
  prior.covariance = Covariance<6>::Identity();
  return prior;
}

Vector<6> detection_at(const Vector3& position) {
  Vector<6> z = Vector<6>::Zero();
  z.head<3>() = position;
  return z;
}

const double kGate = chi_square_quantile(0.9999, 6.0);

TEST(ScanAssignment, EachTrackTakesItsOwnDetectionAndTheRestIsLeftForInitiation) {
  const std::vector<GaussianState<6>> tracks = {track_at({0, 0, 100}), track_at({500, 0, 100})};
  Scan<6> scan{3, Covariance<6>::Identity(), {}};
  scan.detections = {detection_at({9000, 0, 100}), detection_at({500.5, 0, 100}),
                     detection_at({0.3, 0.2, 100})};
  AssignmentWork work;
  const ScanAssignment a =
      assign_scan(std::span<const GaussianState<6>>(tracks), Sensor(), scan, kGate, 4096, work);
  EXPECT_EQ(a.detection_of_track, (std::vector<int>{2, 1}));
  EXPECT_EQ(a.unassociated, (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(a.gated_pairs, 2U);  // the pre-gate kept the far detection from every track
  EXPECT_EQ(a.dropped, 0U);
}

TEST(ScanAssignment, AClutterBurstBeyondTheBoundIsCountedAndLeftOut) {
  const std::vector<GaussianState<6>> tracks = {track_at({0, 0, 100})};
  Scan<6> scan{3, Covariance<6>::Identity(), {}};
  for (int i = 0; i < 5000; ++i) scan.detections.push_back(detection_at({i * 10.0, 7, 100}));
  AssignmentWork work;
  const ScanAssignment a =
      assign_scan(std::span<const GaussianState<6>>(tracks), Sensor(), scan, kGate, 100, work);
  EXPECT_EQ(a.dropped, 4900U);
  EXPECT_EQ(a.detection_of_track.size(), 1U);
  EXPECT_EQ(a.unassociated.size() + (a.detection_of_track[0] >= 0 ? 1U : 0U), 100U);
}

TEST(ScanAssignment, TwoTracksCompetingForOneDetectionGiveItToTheCloser) {
  const std::vector<GaussianState<6>> tracks = {track_at({0, 0, 100}), track_at({2, 0, 100})};
  Scan<6> scan{3, Covariance<6>::Identity(), {}};
  scan.detections = {detection_at({1.4, 0, 100})};
  AssignmentWork work;
  const ScanAssignment a =
      assign_scan(std::span<const GaussianState<6>>(tracks), Sensor(), scan, kGate, 4096, work);
  EXPECT_EQ(a.detection_of_track, (std::vector<int>{-1, 0}));
  EXPECT_EQ(a.largest_cluster, 2U);
  EXPECT_TRUE(a.unassociated.empty());
}

}  // namespace
}  // namespace skyfuse
