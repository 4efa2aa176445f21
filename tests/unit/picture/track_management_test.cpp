#include "skyfuse/picture/track_management.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace skyfuse {
namespace {

// A track started by a hit (as initiation starts one), then `rounds` hits and misses.
std::vector<TrackFate> fates_of(const std::vector<bool>& rounds,
                                const ManagementConfig& config = {}) {
  TrackHistory history;
  TrackStatus status = TrackStatus::kTentative;
  history.record(true);
  std::vector<TrackFate> fates;
  for (const bool hit : rounds) {
    fates.push_back(manage_track(history, status, 3.0, hit, config));
    if (fates.back() == TrackFate::kDeleted) break;
  }
  return fates;
}

TEST(TrackManagement, TwoHitsOfThreeConfirm) {
  EXPECT_EQ(fates_of({true}), std::vector<TrackFate>{TrackFate::kConfirmed});
  EXPECT_EQ(fates_of({false, true}),
            (std::vector<TrackFate>{TrackFate::kKept, TrackFate::kConfirmed}));
}

TEST(TrackManagement, ATentativeTrackThatCannotReachTwoOfThreeIsDeleted) {
  EXPECT_EQ(fates_of({false, false}),
            (std::vector<TrackFate>{TrackFate::kKept, TrackFate::kDeleted}));
}

TEST(TrackManagement, AConfirmedTrackIsDeletedAfterFiveMissesInARow) {
  const auto fates = fates_of({true, false, false, false, true, false, false, false, false, false});
  ASSERT_EQ(fates.size(), 10U);
  EXPECT_EQ(fates.front(), TrackFate::kConfirmed);
  for (std::size_t i = 1; i < 9; ++i) EXPECT_EQ(fates[i], TrackFate::kKept) << i;
  EXPECT_EQ(fates.back(), TrackFate::kDeleted);
}

TEST(TrackManagement, ATrackTooUncertainToMeanAnythingIsDeleted) {
  TrackHistory history;
  TrackStatus status = TrackStatus::kConfirmed;
  // A position variance of 3 * 2e6 m^2: sqrt(6e6) m > 1000 m.
  EXPECT_EQ(manage_track(history, status, 6e6, true, ManagementConfig{}), TrackFate::kDeleted);
}

TEST(TrackIds, AreAFunctionOfTheRoundAndTheDetection) {
  EXPECT_EQ(make_track_id(7, 3, 12), (7ULL << 32U) | (3ULL << 16U) | 12ULL);
  EXPECT_EQ(track_label(make_track_id(7, 3, 12)), "7.3.12");
  EXPECT_LT(make_track_id(7, 65535, 65535), make_track_id(8, 0, 0));  // later rounds sort later
  EXPECT_THROW(make_track_id(1, 70000, 0), std::out_of_range);
}

}  // namespace
}  // namespace skyfuse
