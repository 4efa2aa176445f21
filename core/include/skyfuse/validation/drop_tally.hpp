#pragma once
/// \file
/// Counts dropped samples by kind and decides when a drop is worth a log line: the first of
/// each kind at once, then at most one line per kind and interval, so that a process flooding
/// garbage cannot flood the log too.

#include <chrono>

#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse {

class DropTally {
 public:
  using Clock = std::chrono::steady_clock;
  explicit DropTally(Clock::duration interval = std::chrono::seconds(5)) : interval_(interval) {}

  /// Counts one drop of `kind`. Returns how many drops of that kind the log has not told yet,
  /// this one included, when a line is due now; 0 when it is not.
  std::uint64_t record(DropKind kind, Clock::time_point now = Clock::now()) {
    const auto i = static_cast<std::size_t>(kind);
    ++counts_[i];
    ++untold_[i];
    if (counts_[i] > 1 && now - last_told_[i] < interval_) return 0;
    last_told_[i] = now;
    const std::uint64_t untold = untold_[i];
    untold_[i] = 0;
    return untold;
  }

  const DropCounts& counts() const { return counts_; }

 private:
  Clock::duration interval_;
  DropCounts counts_{};
  DropCounts untold_{};
  std::array<Clock::time_point, kDropKinds> last_told_{};
};

}  // namespace skyfuse
