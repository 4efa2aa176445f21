#include "run/discovery_quiet.hpp"

#include <thread>

namespace skyfuse::harness {

QuietWait wait_until_quiet(const std::function<std::optional<double>()>& cpu_seconds, double cores,
                           std::chrono::milliseconds limit,
                           const std::function<bool()>& keep_waiting) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const double window_s = std::chrono::duration<double>(kQuietWindow).count();
  std::optional<double> before = cpu_seconds();
  QuietWait result;
  while (before && Clock::now() - start < limit && (!keep_waiting || keep_waiting())) {
    std::this_thread::sleep_for(kQuietWindow);
    const std::optional<double> now = cpu_seconds();
    if (!now) break;
    const double used = (*now - *before) / window_s;
    before = now;
    if (used < cores) {
      result.quiet = true;
      break;
    }
  }
  result.waited = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - start);
  return result;
}

}  // namespace skyfuse::harness
