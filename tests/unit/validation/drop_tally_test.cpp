#include "skyfuse/validation/drop_tally.hpp"

#include <gtest/gtest.h>

namespace skyfuse {
namespace {

using namespace std::chrono_literals;

TEST(DropTally, TellsTheFirstDropAtOnceThenAtMostOncePerInterval) {
  DropTally tally(5s);
  const DropTally::Clock::time_point t0{};
  EXPECT_EQ(tally.record(DropKind::kNonFinite, t0 + 1s), 1U);
  EXPECT_EQ(tally.record(DropKind::kNonFinite, t0 + 2s), 0U);
  EXPECT_EQ(tally.record(DropKind::kNonFinite, t0 + 3s), 0U);
  // The next line after the interval says how many went untold, itself included.
  EXPECT_EQ(tally.record(DropKind::kNonFinite, t0 + 7s), 3U);
  EXPECT_EQ(tally.counts()[static_cast<std::size_t>(DropKind::kNonFinite)], 4U);
}

TEST(DropTally, KindsAreLimitedSeparately) {
  DropTally tally(5s);
  const DropTally::Clock::time_point t0{};
  EXPECT_EQ(tally.record(DropKind::kNonFinite, t0 + 1s), 1U);
  EXPECT_EQ(tally.record(DropKind::kWrongRun, t0 + 1s), 1U);
  EXPECT_EQ(tally.counts()[static_cast<std::size_t>(DropKind::kWrongRun)], 1U);
  EXPECT_EQ(tally.counts()[static_cast<std::size_t>(DropKind::kDuplicate)], 0U);
}

}  // namespace
}  // namespace skyfuse
