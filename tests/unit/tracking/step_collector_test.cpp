#include "skyfuse/tracking/step_collector.hpp"

#include <gtest/gtest.h>

namespace skyfuse {
namespace {

TEST(StepCollector, GathersInAscendingIdWhateverTheArrivalOrder) {
  const int ids[] = {7, 2, 5};
  StepCollector<int> c(ids);
  EXPECT_EQ(c.offer(0, 5, 50), std::nullopt);
  EXPECT_EQ(c.offer(0, 7, 70), std::nullopt);
  EXPECT_FALSE(c.complete());
  EXPECT_EQ(c.missing(), std::vector<int>{2});
  EXPECT_EQ(c.offer(0, 2, 20), std::nullopt);
  ASSERT_TRUE(c.complete());
  EXPECT_EQ(std::vector<int>(c.payloads().begin(), c.payloads().end()),
            (std::vector<int>{20, 50, 70}));
}

TEST(StepCollector, SaysWhyASampleIsRefused) {
  const int ids[] = {1, 2};
  StepCollector<int> c(ids);
  c.advance();  // now at step 1
  EXPECT_EQ(c.offer(0, 1, 0), DropKind::kStaleStep);
  EXPECT_EQ(c.offer(3, 1, 0), DropKind::kFutureStep);
  EXPECT_EQ(c.offer(1, 9, 0), DropKind::kUnknownStation);
  EXPECT_EQ(c.offer(1, 2, 22), std::nullopt);
  EXPECT_EQ(c.offer(1, 2, 99), DropKind::kDuplicate);
  EXPECT_EQ(c.payloads()[1], 22);  // the first copy stays
  // Step 2 is kept for later, not refused.
  EXPECT_EQ(c.offer(2, 1, 31), std::nullopt);
  c.advance();
  EXPECT_TRUE(c.filled(0));
  EXPECT_FALSE(c.filled(1));
}

}  // namespace
}  // namespace skyfuse

namespace skyfuse {
namespace {

TEST(StepCollector, KnowsWhoWasAbsentFromTheStepClosedLast) {
  // A new writer may take a silent station's id (a restarted process), so "absent" must mean
  // a closed step without it - never the start of the run, where two writers could race.
  const std::vector<int> ids{1, 2, 3};
  StepCollector<int> c(ids);
  for (int id : ids) EXPECT_FALSE(c.absent_last_step(id)) << "nothing has closed yet";
  EXPECT_FALSE(c.offer(0, 1, 10).has_value());
  EXPECT_FALSE(c.offer(0, 3, 30).has_value());
  c.advance();
  EXPECT_FALSE(c.absent_last_step(1));
  EXPECT_TRUE(c.absent_last_step(2));
  EXPECT_FALSE(c.absent_last_step(3));
  EXPECT_FALSE(c.absent_last_step(99)) << "an unknown id is not a station that fell silent";
  EXPECT_FALSE(c.offer(1, 2, 20).has_value());
  c.advance();
  EXPECT_FALSE(c.absent_last_step(2));
  EXPECT_TRUE(c.absent_last_step(1));
}

}  // namespace
}  // namespace skyfuse

namespace skyfuse {
namespace {

TEST(StepCollector, WithALagTakesLateSamplesForTheStepsClosedLast) {
  const std::vector<int> ids{1, 2};
  StepCollector<int> c(ids, 2);
  EXPECT_EQ(c.lag(), 2U);
  EXPECT_EQ(c.offer(0, 1, 10), std::nullopt);
  c.advance();
  c.advance();
  c.advance();  // at step 3: steps 1 and 2 closed within the lag, step 0 past it
  EXPECT_EQ(c.current_step(), 3U);
  EXPECT_EQ(c.offer(0, 2, 20), DropKind::kStaleStep) << "too late for the lag";
  EXPECT_FALSE(c.has_step(0));
  EXPECT_EQ(c.offer(1, 2, 21), std::nullopt) << "late, within the lag";
  EXPECT_EQ(c.offer(1, 2, 99), DropKind::kDuplicate);
  EXPECT_EQ(c.offer(2, 1, 12), std::nullopt);
  EXPECT_EQ(c.offer(4, 1, 14), std::nullopt) << "the next step, as without a lag";
  EXPECT_EQ(c.offer(5, 1, 15), DropKind::kFutureStep);
  ASSERT_TRUE(c.has_step(1));
  EXPECT_FALSE(c.filled_at(1, 0));
  EXPECT_TRUE(c.filled_at(1, 1));
  EXPECT_EQ(c.payload_at(1, 1), 21);
  EXPECT_EQ(c.payload_at(2, 0), 12);
  EXPECT_EQ(c.count(), 0U) << "late samples do not fill the current step";
  c.advance();  // step 4 current, with what arrived early; step 1 leaves the lag
  EXPECT_TRUE(c.filled(0));
  EXPECT_FALSE(c.has_step(1));
  EXPECT_EQ(c.offer(1, 1, 11), DropKind::kStaleStep);
  EXPECT_TRUE(c.has_step(2));
  EXPECT_EQ(c.payload_at(2, 0), 12);
}

}  // namespace
}  // namespace skyfuse
