#pragma once
/// \file
/// When a step begins in real-time mode: every node, and the harness, count from the epoch the
/// start tick carries, so step k begins at epoch + k dt on each machine's system clock.

#include <chrono>
#include <cmath>
#include <cstdint>

namespace skyfuse::transport {

inline std::chrono::system_clock::time_point step_start(std::uint64_t epoch_ns, std::uint64_t step,
                                                        double time_step_s) {
  const double offset_ns = static_cast<double>(step) * time_step_s * 1e9;
  return std::chrono::system_clock::time_point(
      std::chrono::nanoseconds(epoch_ns + static_cast<std::uint64_t>(std::llround(offset_ns))));
}

/// How long `steps` steps last: what a node waits, after its last round, for the samples a
/// re-fusion lag of that many steps may still take.
inline std::chrono::microseconds steps_duration(std::uint64_t steps, double time_step_s) {
  return std::chrono::duration_cast<std::chrono::microseconds>(
      std::chrono::duration<double>(static_cast<double>(steps) * time_step_s));
}

}  // namespace skyfuse::transport
