#include "skyfuse/asterix/track_numbers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

namespace skyfuse::asterix {
namespace {

TEST(TrackNumbers, NewTracksTakeTheLowestNumbersInAscendingId) {
  TrackNumbers numbers;
  numbers.update(std::vector<std::uint64_t>{900000000002, 900000000017, 900000000040}, 0);
  EXPECT_EQ(numbers.number_of(900000000002), 1);
  EXPECT_EQ(numbers.number_of(900000000017), 2);
  EXPECT_EQ(numbers.number_of(900000000040), 3);
  EXPECT_EQ(numbers.number_of(5), std::nullopt);
  // A track keeps its number while it lasts; the next new one takes 4.
  numbers.update(std::vector<std::uint64_t>{900000000002, 900000000017, 900000000040, 900000000041},
                 1);
  EXPECT_EQ(numbers.number_of(900000000017), 2);
  EXPECT_EQ(numbers.number_of(900000000041), 4);
}

TEST(TrackNumbers, AGoneTracksNumberIsHeldOffThenTheLowestFree) {
  TrackNumbers numbers(1, 100, 3);
  numbers.update(std::vector<std::uint64_t>{10, 20, 30}, 0);
  numbers.update(std::vector<std::uint64_t>{10, 30}, 1);  // 20 went: number 2 held until round 4
  EXPECT_EQ(numbers.number_of(20), std::nullopt);
  numbers.update(std::vector<std::uint64_t>{10, 30, 40}, 2);
  EXPECT_EQ(numbers.number_of(40), 4) << "2 is held off";
  numbers.update(std::vector<std::uint64_t>{10, 30, 40, 50}, 4);
  EXPECT_EQ(numbers.number_of(50), 2) << "free again three rounds after its track went";
}

TEST(TrackNumbers, NodesFedTheSamePicturesNumberThemAlike) {
  TrackNumbers mine(1, 40, 2);
  TrackNumbers theirs(1, 40, 2);
  std::vector<std::uint64_t> ids;
  for (std::uint64_t round = 0; round < 200; ++round) {
    // Tracks come and go: id i lives from round i/2 to round i/2 + 7 + i % 11.
    ids.clear();
    for (std::uint64_t i = 0; i < 2 * round + 2; ++i) {
      if (round >= i / 2 && round < i / 2 + 7 + i % 11) ids.push_back(1000 + i);
    }
    mine.update(ids, round);
    theirs.update(ids, round);
    std::vector<std::uint16_t> in_use;
    for (const std::uint64_t id : ids) {
      ASSERT_EQ(mine.number_of(id), theirs.number_of(id)) << "round " << round;
      ASSERT_TRUE(mine.number_of(id).has_value()) << "round " << round;
      in_use.push_back(*mine.number_of(id));
    }
    std::sort(in_use.begin(), in_use.end());
    ASSERT_EQ(std::adjacent_find(in_use.begin(), in_use.end()), in_use.end())
        << "round " << round << ": one number, one track";
  }
}

// A node that restarts at round 100 and takes its peer's state then numbers every later round
// as the peer does; one that starts afresh does not.
TEST(TrackNumbers, ANodeThatTakesAPeersStateNumbersTheNextRoundsAlike) {
  TrackNumbers peer(1, 40, 2);
  TrackNumbers restarted(1, 40, 2);
  TrackNumbers afresh(1, 40, 2);
  std::vector<std::uint64_t> ids;
  int afresh_differs = 0;
  for (std::uint64_t round = 0; round < 200; ++round) {
    ids.clear();
    for (std::uint64_t i = 0; i < 2 * round + 2; ++i) {
      if (round >= i / 2 && round < i / 2 + 7 + i % 11) ids.push_back(1000 + i);
    }
    peer.update(ids, round);
    if (round == 100) {
      restarted.restore(peer.state());
      EXPECT_EQ(restarted.state(), peer.state());
    } else if (round > 100) {
      restarted.update(ids, round);
      afresh.update(ids, round);
      for (const std::uint64_t id : ids) {
        ASSERT_EQ(restarted.number_of(id), peer.number_of(id)) << "round " << round;
        if (afresh.number_of(id) != peer.number_of(id)) ++afresh_differs;
      }
    }
  }
  EXPECT_GT(afresh_differs, 0) << "without the state, the numbers part";
}

TEST(TrackNumbers, MoreTracksThanNumbersLeaveTheNewestWithoutOneUntilOneFrees) {
  TrackNumbers numbers(1, 2, 1);
  numbers.update(std::vector<std::uint64_t>{1, 2, 3}, 0);
  EXPECT_EQ(numbers.number_of(3), std::nullopt);
  EXPECT_EQ(numbers.unnumbered(), 1U);
  numbers.update(std::vector<std::uint64_t>{2, 3}, 1);  // 1 went; its number held one round
  EXPECT_EQ(numbers.number_of(3), std::nullopt);
  numbers.update(std::vector<std::uint64_t>{2, 3}, 2);
  EXPECT_EQ(numbers.number_of(3), 1);
  EXPECT_EQ(numbers.unnumbered(), 0U);
  EXPECT_THROW(TrackNumbers(0, 10, 1), std::invalid_argument);
  EXPECT_THROW(TrackNumbers(5, 4, 1), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse::asterix
