#pragma once
// One DDS run of the system: M station processes and the fusion center started (or, with
// `external`, found), driven in lock-step or real time, recorded and reported. `skyfuse run`,
// `skyfuse demo` and `skyfuse bench` all run the system through this.

#include <utility>
#include <vector>

#include "run/lockstep_driver.hpp"
#include "run/placement.hpp"
#include "run/run_options.hpp"
#include "run/run_report.hpp"
#include "run/run_stopped_early.hpp"
#include "skyfuse/sim/run_plan.hpp"

namespace skyfuse::harness {

/// Seconds to wait until every process has joined: the option if given, else
/// default_discovery_timeout_s(stations).
double discovery_timeout_s(const RunOptions& options, int stations);

/// Tells the user on stderr when `stations` stations need larger socket buffers than the
/// kernel grants (transport::receive_buffer_warning); says nothing otherwise.
void warn_if_receive_buffers_too_small(int stations);

/// The run's plan from the options' scenario (or the embedded one) and overrides; refuses a
/// configuration the wire cannot carry yet, before any process starts.
RunPlan load_run_plan(const RunOptions& options);

/// Kills and restarts must name participants (`participant_ids`), fit in a run of `steps`,
/// and alternate per station: kill, restart later, kill again later, ... Throws
/// std::invalid_argument naming the option otherwise.
void check_station_events(const RunOptions& o, const std::vector<int>& participant_ids, int steps);

/// The harness's own DDS participant for a run of `stations` placed by `placement`: the run's
/// domain, QoS file, reliability, network, lease, discovery server and security identity.
transport::NodeConfig harness_node_config(const RunOptions& o, const Placement& placement,
                                          int stations);

/// The exit status of `skyfuse run` (and the commands that run the system) for a run that
/// ended with `e`: 128 + the signal when interrupted (130 for Ctrl-C), kExitStoppedEarly when
/// it fell behind real time or a node went silent, 1 otherwise (a node failed, discovery did
/// not complete, ...).
int exit_status_of(const RunAborted& e);
inline constexpr int kExitStoppedEarly = 3;

/// One DDS run of `plan` with results written to options.out_dir; throws RunAborted on
/// failure, RunStoppedEarly when the rounds began but did not all complete (with the files
/// written: StoppedEarlyWith<RunSummary>). A secure run is started again after a stalled start
/// while --discovery-timeout lasts (secure_start.hpp).
RunSummary execute_run(const RunOptions& options, const RunPlan& plan);

}  // namespace skyfuse::harness
