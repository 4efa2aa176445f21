#include "skyfuse/picture/associators/gnn.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "unit/picture/associators/association_fixture.hpp"

namespace skyfuse {
namespace {

using testing::decide;
using testing::detection_at;
using testing::scan_of;
using testing::track_at;

// (track, detection) of each pair, every weight checked to be 1.
std::vector<std::pair<int, std::uint32_t>> pairs_of(const ScanAssociation& a) {
  std::vector<std::pair<int, std::uint32_t>> pairs;
  for (const WeightedPair& p : a.pairs) {
    EXPECT_EQ(p.weight, 1.0);
    pairs.emplace_back(p.track, p.detection);
  }
  return pairs;
}

TEST(GnnAssociator, EachTrackTakesItsOwnDetectionAndTheRestIsLeftForInitiation) {
  const std::vector<GaussianState<6>> tracks = {track_at({0, 0, 100}), track_at({500, 0, 100})};
  const ScanAssociation a =
      decide("gnn", tracks,
             scan_of({detection_at({9000, 0, 100}), detection_at({500.5, 0, 100}),
                      detection_at({0.3, 0.2, 100})}));
  EXPECT_EQ(pairs_of(a), (std::vector<std::pair<int, std::uint32_t>>{{0, 2}, {1, 1}}));
  EXPECT_EQ(a.unassociated, (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(a.gated_pairs, 2U);  // the pre-gate kept the far detection from every track
  EXPECT_EQ(a.dropped, 0U);
}

TEST(GnnAssociator, AClutterBurstBeyondTheBoundIsCountedAndLeftOut) {
  const std::vector<GaussianState<6>> tracks = {track_at({0, 0, 100})};
  std::vector<Vector<6>> burst;
  for (int i = 0; i < 5000; ++i) burst.push_back(detection_at({i * 10.0, 7, 100}));
  const ScanAssociation a = decide("gnn", tracks, scan_of(std::move(burst)), 100);
  EXPECT_EQ(a.dropped, 4900U);
  EXPECT_LE(a.pairs.size(), 1U);
  EXPECT_EQ(a.unassociated.size() + a.pairs.size(), 100U);
}

TEST(GnnAssociator, TwoTracksCompetingForOneDetectionGiveItToTheCloser) {
  const std::vector<GaussianState<6>> tracks = {track_at({0, 0, 100}), track_at({2, 0, 100})};
  const ScanAssociation a = decide("gnn", tracks, scan_of({detection_at({1.4, 0, 100})}));
  EXPECT_EQ(pairs_of(a), (std::vector<std::pair<int, std::uint32_t>>{{1, 0}}));
  EXPECT_EQ(a.largest_cluster, 2U);
  EXPECT_TRUE(a.unassociated.empty());
}

}  // namespace
}  // namespace skyfuse
