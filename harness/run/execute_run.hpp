#pragma once
// One DDS run of one aircraft: M station processes and the fusion center started (or, with
// `external`, found), driven in lock-step or real time, recorded and reported — the house
// (run_over_dds.hpp) given one aircraft's kind: every node's track of each round recorded
// (RunRecorder), streamed live and written as the per-step CSVs. `skyfuse run`, `skyfuse demo`
// and `skyfuse bench` run one aircraft through this; picture_run.hpp runs many.

#include <utility>
#include <vector>

#include "run/lockstep_driver.hpp"
#include "run/placement.hpp"
#include "run/run_options.hpp"
#include "run/run_over_dds.hpp"
#include "run/run_report.hpp"
#include "run/run_stopped_early.hpp"
#include "skyfuse/sim/run_plan.hpp"

namespace skyfuse::harness {

/// Tells the user on stderr when `stations` stations need larger socket buffers than the
/// kernel grants (transport::receive_buffer_warning); says nothing otherwise.
void warn_if_receive_buffers_too_small(int stations);

/// One DDS run of `plan` with results written to options.out_dir; throws RunAborted on
/// failure, RunStoppedEarly when the rounds began but did not all complete (with the files
/// written: StoppedEarlyWith<RunSummary>). A secure run is started again after a stalled start
/// while --discovery-timeout lasts (secure_start.hpp).
RunSummary execute_run(const RunOptions& options, const RunPlan& plan);

}  // namespace skyfuse::harness
