#include "skyfuse/metrics/picture_score.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace skyfuse {
namespace {

constexpr GospaParameters kGospa{.cutoff_m = 10.0, .order = 2.0};

// Three aircraft, the third out of every station's view; a track on each of the first and
// third, and a false one far from all.
const std::vector<TruthPoint> kAircraft = {
    {0, {0, 0, 0}, true}, {1, {100, 0, 0}, true}, {2, {0, 500, 0}, false}};
const std::vector<TrackPoint> kTracks = {{11, {3, 0, 0}}, {12, {0, 504, 0}}, {13, {900, 900, 0}}};

TEST(PictureScore, GospaOverEveryAircraftCountsTheOnesNoStationSees) {
  PictureScore score(kGospa, kAircraft.size(), 1.0);
  const PictureStep& step = score.add_step(0, kAircraft, kTracks);
  // Pairs (0, 11) at 3 m and (2, 12) at 4 m; aircraft 1 missed; track 13 false.
  EXPECT_EQ(step.gospa.assigned, 2U);
  EXPECT_DOUBLE_EQ(step.gospa.localisation, 9.0 + 16.0);
  EXPECT_DOUBLE_EQ(step.gospa.missed, 50.0);
  EXPECT_DOUBLE_EQ(step.gospa.false_tracks, 50.0);
  EXPECT_DOUBLE_EQ(step.gospa.distance, std::sqrt(125.0));
}

TEST(PictureScore, GospaInViewLeavesOutTheAircraftOutOfViewAndTheirTracks) {
  PictureScore score(kGospa, kAircraft.size(), 1.0);
  const PictureStep& step = score.add_step(0, kAircraft, kTracks);
  // Aircraft 2 is out of view, and track 12 coasts on it: neither counts. Track 13, on no
  // aircraft, is still false.
  EXPECT_EQ(step.gospa_in_view.assigned, 1U);
  EXPECT_DOUBLE_EQ(step.gospa_in_view.localisation, 9.0);
  EXPECT_EQ(step.gospa_in_view.missed_targets, 1U);
  EXPECT_EQ(step.gospa_in_view.false_estimates, 1U);
  EXPECT_DOUBLE_EQ(step.gospa_in_view.distance, std::sqrt(9.0 + 50.0 + 50.0));
}

TEST(PictureScore, GospaOverTheAddressedLeavesOutTheSilentAndTheirTracks) {
  std::vector<TruthPoint> aircraft = kAircraft;
  aircraft[0].addressed = true;
  std::vector<TrackPoint> tracks = kTracks;
  tracks.push_back({14, {100, 2, 0}});  // on aircraft 1, in view but silent
  PictureScore score(kGospa, aircraft.size(), 1.0);
  const PictureStep& step = score.add_step(0, aircraft, tracks);
  // Only aircraft 0 counts, with its track 11 at 3 m; tracks 12 (out of view) and 14 (on the
  // silent aircraft) are left out; track 13, on no aircraft, is false.
  const Gospa& g = step.gospa_addressed_in_view;
  EXPECT_EQ(g.assigned, 1U);
  EXPECT_DOUBLE_EQ(g.localisation, 9.0);
  EXPECT_EQ(g.missed_targets, 0U);
  EXPECT_EQ(g.false_estimates, 1U);
  EXPECT_DOUBLE_EQ(g.distance, std::sqrt(59.0));
  EXPECT_DOUBLE_EQ(score.summary().addressed_in_view.distance, std::sqrt(59.0));
}

TEST(PictureScore, EveryAircraftInViewGivesTheSameGospaTwice) {
  std::vector<TruthPoint> aircraft = kAircraft;
  aircraft[2].in_view = true;
  PictureScore score(kGospa, aircraft.size(), 1.0);
  const PictureStep& step = score.add_step(0, aircraft, kTracks);
  EXPECT_EQ(step.gospa_in_view.distance, step.gospa.distance);
  EXPECT_EQ(step.gospa_in_view.localisation, step.gospa.localisation);
}

TEST(PictureScore, TheSummaryAveragesBothOverTheSteps) {
  PictureScore score(kGospa, kAircraft.size(), 1.0);
  score.add_step(0, kAircraft, kTracks);
  score.add_step(1, kAircraft, {});  // no track: every aircraft missed
  const PictureSummary s = score.summary();
  EXPECT_DOUBLE_EQ(s.gospa_mean, (std::sqrt(125.0) + std::sqrt(150.0)) / 2.0);
  EXPECT_DOUBLE_EQ(s.in_view.distance, (std::sqrt(109.0) + std::sqrt(100.0)) / 2.0);
  EXPECT_DOUBLE_EQ(s.in_view.missed, (50.0 + 100.0) / 2.0);
  EXPECT_DOUBLE_EQ(s.in_view.false_tracks, 50.0 / 2.0);
}

TEST(PictureScore, ASecondTrackOnOneAircraftIsCountedAsADuplicateEachStep) {
  PictureScore score(kGospa, kAircraft.size(), 1.0);
  const std::vector<TrackPoint> twice = {{11, {3, 0, 0}}, {14, {0, 2, 0}}, {12, {0, 504, 0}}};
  score.add_step(0, kAircraft, twice);
  score.add_step(1, kAircraft, twice);
  score.add_step(2, kAircraft, kTracks);  // one track each again
  const PictureSummary s = score.summary();
  EXPECT_EQ(s.duplicate_track_steps, 2U);
  EXPECT_EQ(s.duplicate_track_steps_addressed, 0U);

  std::vector<TruthPoint> addressed = kAircraft;
  addressed[0].addressed = true;
  PictureScore of_addressed(kGospa, kAircraft.size(), 1.0);
  of_addressed.add_step(0, addressed, twice);
  EXPECT_EQ(of_addressed.summary().duplicate_track_steps_addressed, 1U);
  EXPECT_DOUBLE_EQ(s.ambiguity, 8.0 / 6.0);
}

// Two aircraft 6 m apart, a track 4 m from one and 2 m from the other, a second 1 m beyond the
// other: both tracks are nearest the second aircraft (ambiguity 2), but GOSPA pairs each aircraft
// with a track of its own, and no track is a duplicate.
TEST(PictureScore, TwoAircraftPassingCloseWithATrackEachHaveNoDuplicate) {
  const std::vector<TruthPoint> close = {{0, {0, 0, 0}, true, true}, {1, {6, 0, 0}, true, true}};
  const std::vector<TrackPoint> each = {{21, {4, 0, 0}}, {22, {7, 0, 0}}};
  PictureScore score(kGospa, close.size(), 1.0);
  const PictureStep& step = score.add_step(0, close, each);
  EXPECT_EQ(step.gospa.assigned, 2U);
  const PictureSummary s = score.summary();
  EXPECT_DOUBLE_EQ(s.ambiguity, 2.0);
  EXPECT_EQ(s.duplicate_track_steps, 0U);
  EXPECT_EQ(s.duplicate_track_steps_addressed, 0U);
}

}  // namespace
}  // namespace skyfuse
