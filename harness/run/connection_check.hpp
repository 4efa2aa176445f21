#pragma once
// The first rounds of a lock-step run without loss are complete in a connected network; if none
// is, some pair of processes never matched (seen with secure discovery), and every round would
// wait for its deadline. Better to say so at once. With reliable samples one round tells; best
// effort may lose a sample of round 0 while the sockets still fill (seen at M = 64 on a slow
// host), which is a loss, not a broken network: it gets a few rounds. And a large run's first
// rounds may run beside the last of discovery: at M = 256 in 17 processes the endpoints'
// announcements went on for the first rounds (66 000 datagrams a round), and the clusters' sums
// came after their stage had closed. So the first rounds may all be incomplete for
// kConnectionGrace too. Both kinds of run check their rounds so.

#include <fmt/format.h>

#include <chrono>
#include <optional>
#include <string>

#include "run/run_aborted.hpp"

namespace skyfuse::harness {

/// How long the first rounds of a lock-step run may all be incomplete before the network counts
/// as not fully connected (with at least connection_rounds_of() rounds).
inline constexpr std::chrono::seconds kConnectionGrace{60};

/// How many first rounds of a lock-step run without loss may all be incomplete before it is
/// stopped as not fully connected: one with reliable samples; with best-effort ones, whose
/// first round may lose a sample while the sockets fill, a few.
inline int connection_rounds_of(bool best_effort) {
  constexpr int kBestEffortConnectionRounds = 5;
  return best_effort ? kBestEffortConnectionRounds : 1;
}

class ConnectionCheck {
 public:
  /// `checking`: whether the run's rounds should all be complete (lock-step, without loss);
  /// `best_effort`: whether its samples are; `grace`: how long from now they may all be
  /// incomplete.
  ConnectionCheck(bool checking, bool best_effort,
                  std::chrono::milliseconds grace = kConnectionGrace)
      : rounds_(connection_rounds_of(best_effort)), checking_(checking), grace_(grace) {}

  /// Round k, with what it lacks (nothing when every node delivered and fused every station):
  /// throws RunAborted when it and every round before it were incomplete for long enough.
  void take(int k, const std::optional<std::string>& missing) {
    if (!checking_) return;
    if (!missing) {
      checking_ = false;
      return;
    }
    if (k + 1 >= rounds_ && std::chrono::steady_clock::now() - first_round_ >= grace_) {
      throw RunAborted(fmt::format("{}, the network is not fully connected: {}",
                                   rounds_ == 1 ? std::string("round 0 incomplete")
                                                : fmt::format("rounds 0-{} all incomplete", k),
                                   *missing));
    }
  }

 private:
  int rounds_;
  bool checking_;
  std::chrono::milliseconds grace_;
  std::chrono::steady_clock::time_point first_round_ = std::chrono::steady_clock::now();
};

}  // namespace skyfuse::harness
