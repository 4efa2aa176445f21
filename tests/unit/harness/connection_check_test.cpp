// Both kinds of run stop a lock-step run whose first rounds are all incomplete as not fully
// connected, but only once enough rounds (one reliable, five best effort) and the grace have
// passed; a complete round ends the checking for good.
#include "run/connection_check.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace skyfuse::harness {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

const std::optional<std::string> kShort = std::string("station 2: 3 of 4 scans");

constexpr bool kChecking = true;
constexpr bool kReliable = false;
constexpr bool kBestEffort = true;

TEST(ConnectionCheck, AnIncompleteFirstRoundPastTheGraceStopsTheRunNamingWhatWasMissing) {
  ConnectionCheck check(kChecking, kReliable, 0ms);
  try {
    check.take(0, kShort);
    FAIL() << "round 0 incomplete past the grace did not stop the run";
  } catch (const RunAborted& e) {
    EXPECT_THAT(e.what(), HasSubstr("round 0 incomplete, the network is not fully connected: "
                                    "station 2: 3 of 4 scans"));
  }
}

TEST(ConnectionCheck, WithinTheGraceIncompleteRoundsGoOn) {
  ConnectionCheck check(kChecking, kReliable, 1h);
  for (int k = 0; k < 20; ++k) EXPECT_NO_THROW(check.take(k, kShort)) << k;
}

TEST(ConnectionCheck, BestEffortGetsFiveRoundsBeforeItCounts) {
  ConnectionCheck check(kChecking, kBestEffort, 0ms);
  for (int k = 0; k < 4; ++k) EXPECT_NO_THROW(check.take(k, kShort)) << k;
  EXPECT_THROW(check.take(4, kShort), RunAborted);
}

TEST(ConnectionCheck, OneCompleteRoundEndsTheChecking) {
  ConnectionCheck check(kChecking, kReliable, 0ms);
  EXPECT_NO_THROW(check.take(0, std::nullopt));
  EXPECT_NO_THROW(check.take(1, kShort));
}

TEST(ConnectionCheck, ARunWithLossOrOnTheWallClockIsNotChecked) {
  ConnectionCheck check(!kChecking, kReliable, 0ms);
  EXPECT_NO_THROW(check.take(0, kShort));
}

}  // namespace
}  // namespace skyfuse::harness
