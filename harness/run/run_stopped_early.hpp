#pragma once
// A run that stopped before its last round once its rounds had begun, whichever its kind: it
// fell behind real time, a node went silent past --round-timeout, a signal interrupted it, or a
// node failed. The nodes were stopped and every file written with the rounds recorded; the
// command prints its table from summary() and main says why it stopped.

#include <string>
#include <utility>

#include "run/run_aborted.hpp"

namespace skyfuse::harness {

class RunStoppedEarly : public RunAborted {
 public:
  RunStoppedEarly(const RunAborted& why, std::string host_verdict)
      : RunAborted(why.what(), why.cause()), host_verdict_(std::move(host_verdict)) {}
  /// What the run says of the host that could not carry it; empty when nothing.
  const std::string& host_verdict() const { return host_verdict_; }

 private:
  std::string host_verdict_;
};

/// The same, with what summary.json says of the run (RunSummary, PictureRunSummary).
template <typename Summary>
class StoppedEarlyWith : public RunStoppedEarly {
 public:
  StoppedEarlyWith(const RunAborted& why, Summary summary, std::string host_verdict = {})
      : RunStoppedEarly(why, std::move(host_verdict)), summary_(std::move(summary)) {}
  const Summary& summary() const { return summary_; }

 private:
  Summary summary_;
};

}  // namespace skyfuse::harness
