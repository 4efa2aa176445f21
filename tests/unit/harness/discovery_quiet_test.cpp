// The harness starts the rounds once the run's processes have gone quiet after every node
// joined: the first window in which they used less than the bound of a core ends the wait; a
// run that never goes quiet starts at the limit, and one whose CPU time cannot be read at once.
#include "run/discovery_quiet.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <vector>

namespace skyfuse::harness {
namespace {

using namespace std::chrono_literals;

// CPU seconds that come as `totals` in turn (the last one ever after), counting the reads.
struct ScriptedCpu {
  std::vector<std::optional<double>> totals;
  std::size_t reads = 0;
  std::optional<double> operator()() {
    const std::size_t i = std::min(reads, totals.size() - 1);
    ++reads;
    return totals[i];
  }
};

TEST(DiscoveryQuiet, TheFirstQuietWindowEndsTheWait) {
  // Windows of 250 ms: two cores busy twice (0.5 s of CPU each), then 0.01 s (4 % of a core).
  ScriptedCpu cpu{{0.0, 0.5, 1.0, 1.01, 1.02}};
  const QuietWait wait = wait_until_quiet(std::ref(cpu), 0.1, 30s);
  EXPECT_TRUE(wait.quiet);
  EXPECT_EQ(cpu.reads, 4u);  // the start and three windows
}

TEST(DiscoveryQuiet, ARunThatStaysBusyStartsAtTheLimit) {
  std::vector<std::optional<double>> busy;
  for (int i = 0; i < 100; ++i) busy.push_back(0.5 * i);
  ScriptedCpu cpu{busy};
  const QuietWait wait = wait_until_quiet(std::ref(cpu), 0.1, 600ms);
  EXPECT_FALSE(wait.quiet);
  EXPECT_GE(wait.waited, 600ms);
  EXPECT_LE(cpu.reads, 5u);  // the start and at most four windows of 250 ms
}

TEST(DiscoveryQuiet, AnUnreadableCpuTimeEndsTheWaitAtOnce) {
  ScriptedCpu cpu{{std::nullopt}};
  const QuietWait wait = wait_until_quiet(std::ref(cpu), 0.1, 30s);
  EXPECT_FALSE(wait.quiet);
  EXPECT_EQ(cpu.reads, 1u);
}

TEST(DiscoveryQuiet, AStopEndsTheWait) {
  ScriptedCpu cpu{{0.0, 0.5, 1.0, 1.5}};
  int asked = 0;
  const QuietWait wait = wait_until_quiet(std::ref(cpu), 0.1, 30s, [&] { return ++asked < 2; });
  EXPECT_FALSE(wait.quiet);
  EXPECT_EQ(cpu.reads, 2u);  // the start and one window, then the stop
}

TEST(DiscoveryQuiet, TheBoundGrowsWithTheProcessesButStaysBelowACore) {
  EXPECT_DOUBLE_EQ(quiet_cores(0), 0.1);
  EXPECT_LT(quiet_cores(18), quiet_cores(66));
  EXPECT_LT(quiet_cores(66), 1.0);  // M = 64, one process per station: below one busy core
}

}  // namespace
}  // namespace skyfuse::harness
