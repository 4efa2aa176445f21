// transport::admit, the last stage of every receiver's screening: the step window first, then
// whether the writer speaks for the station it names, then the collector's own duplicate check.
#include "skyfuse/transport/source_binding.hpp"

#include <gtest/gtest.h>

#include <array>

namespace skyfuse::transport {
namespace {

const std::array<int, 2> kStations{1, 2};

WriterId writer(std::uint8_t tag) {
  WriterId id{};
  id[15] = tag;
  return id;
}

TEST(Admit, AStationSpeaksThroughTheFirstWriterHeardForIt) {
  StepCollector<int> collector(kStations);
  SourceBinding sources;
  EXPECT_EQ(admit(collector, sources, 0, 1, writer(1), 10), std::nullopt);
  // Another writer naming station 1, for a step still open, is an impersonation.
  EXPECT_EQ(admit(collector, sources, 1, 1, writer(9), 11), DropKind::kDuplicate);
  EXPECT_EQ(admit(collector, sources, 1, 1, writer(1), 12), std::nullopt);
  // The same writer twice for one step is a duplicate by the collector.
  EXPECT_EQ(admit(collector, sources, 0, 1, writer(1), 13), DropKind::kDuplicate);
  EXPECT_EQ(collector.payloads()[0], 10);
}

TEST(Admit, TheStepWindowIsCheckedBeforeTheWriter) {
  StepCollector<int> collector(kStations);
  SourceBinding sources;
  ASSERT_EQ(admit(collector, sources, 0, 1, writer(1), 10), std::nullopt);
  ASSERT_EQ(admit(collector, sources, 0, 2, writer(2), 20), std::nullopt);
  ASSERT_EQ(admit(collector, sources, 1, 1, writer(1), 11), std::nullopt);
  ASSERT_EQ(admit(collector, sources, 1, 2, writer(2), 21), std::nullopt);
  collector.advance();
  collector.advance();  // steps 0 and 1 closed, both stations in each
  EXPECT_EQ(admit(collector, sources, 1, 1, writer(9), 11), DropKind::kStaleStep);
  EXPECT_EQ(admit(collector, sources, 4, 1, writer(9), 11), DropKind::kFutureStep);
  EXPECT_EQ(admit(collector, sources, 2, 7, writer(9), 11), DropKind::kUnknownStation);
  EXPECT_EQ(admit(collector, sources, 2, 1, writer(9), 11), DropKind::kDuplicate);
}

TEST(Admit, ANewWriterTakesOverOnlyAStationSilentInTheLastClosedStep) {
  StepCollector<int> collector(kStations);
  SourceBinding sources;
  // At the start nobody counts as absent: a second writer cannot take station 2.
  ASSERT_EQ(admit(collector, sources, 0, 2, writer(2), 20), std::nullopt);
  EXPECT_EQ(admit(collector, sources, 1, 2, writer(3), 21), DropKind::kDuplicate);
  collector.advance();  // step 0 closed with station 2 in it
  EXPECT_EQ(admit(collector, sources, 1, 2, writer(3), 21), DropKind::kDuplicate);
  collector.advance();  // step 1 closed without station 2: its process died
  EXPECT_EQ(admit(collector, sources, 2, 2, writer(3), 22), std::nullopt);  // the restart
  collector.advance();  // step 2 closed with the new process in it
  // From now on the old writer is the stranger (its slot for step 3 is still empty).
  EXPECT_EQ(admit(collector, sources, 3, 2, writer(2), 23), DropKind::kDuplicate);
  EXPECT_EQ(admit(collector, sources, 3, 2, writer(3), 23), std::nullopt);
}

}  // namespace
}  // namespace skyfuse::transport
