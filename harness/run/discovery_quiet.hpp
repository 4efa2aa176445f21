#pragma once
// After every node has announced READY, discovery may not be over: a node is ready once its own
// endpoints have matched what its rounds need, while the participants go on announcing their
// other endpoints to each other. At M = 256 in 17 processes of 16 stations that went on for
// about 30 s (66 000 to 79 000 datagrams a round, both cores busy), and the rounds run meanwhile
// were incomplete. So the harness starts the rounds once the run's processes have gone quiet.
//
// Quiet is measured on the run's own processes, as the CPU time they use over windows of
// kQuietWindow: the kernel's datagram counters cover a whole network namespace, where another
// run or any DDS program on the host (a test beside this one, a reader of another DDS) keeps
// them busy. Idle, a node's threads only wake for timers and the periodic announcements.

#include <chrono>
#include <cstddef>
#include <functional>
#include <optional>

namespace skyfuse::harness {

inline constexpr std::chrono::milliseconds kQuietWindow{250};

/// The share of one core below which a run of `processes` processes counts as quiet: a tenth of
/// a core, and half a percent more for each process (their idle timers).
inline double quiet_cores(std::size_t processes) {
  return 0.1 + 0.005 * static_cast<double>(processes);
}

struct QuietWait {
  std::chrono::milliseconds waited{0};
  bool quiet = false;  ///< false: `limit` passed first (or the CPU time could not be read)
};

/// Reads `cpu_seconds` (the run's processes' CPU time so far) every kQuietWindow until one
/// window used less than `cores` of a core, at most for `limit`; `keep_waiting` is asked between
/// windows and ends the wait early when false (a stop, a failed node).
QuietWait wait_until_quiet(const std::function<std::optional<double>()>& cpu_seconds, double cores,
                           std::chrono::milliseconds limit,
                           const std::function<bool()>& keep_waiting = {});

}  // namespace skyfuse::harness
