#pragma once
// How a run ends before its last round, for either kind of run and whichever part of the
// harness notices: the cause, as a program reads it and as summary.json's `ended` says it.

#include <stdexcept>
#include <string>
#include <string_view>

namespace skyfuse::harness {

/// Why a run stopped before its last round (kError: anything that is not one of the others,
/// such as discovery that never completed).
enum class StopCause {
  kError,
  kFellBehind,    ///< real time: the nodes fell further behind the schedule than allowed
  kRoundTimeout,  ///< lock-step: a running node delivered nothing for --round-timeout
  kInterrupted,   ///< a signal (Ctrl-C, SIGTERM) to the harness
  kNodeFailed,    ///< a node exited, was killed by a signal, or reported failure
};

/// "fell_behind", "round_timeout", ...: summary.json's `ended`.
std::string_view to_string(StopCause cause);

/// A run was abandoned: a child died, a node reported failure, time ran out, or the user
/// interrupted. The message says which; cause() says it to the program.
class RunAborted : public std::runtime_error {
 public:
  explicit RunAborted(const std::string& what, StopCause cause = StopCause::kError)
      : std::runtime_error(what), cause_(cause) {}
  StopCause cause() const { return cause_; }

 private:
  StopCause cause_;
};

}  // namespace skyfuse::harness
