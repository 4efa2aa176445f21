#pragma once
// `skyfuse run`: the system as it is meant to run - one process per station plus the fusion
// center, over DDS, driven in lock-step by this harness.

#include <CLI/App.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "run_report.hpp"
#include "skyfuse/random/link_loss.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/validation/nis_gate.hpp"

namespace skyfuse::harness {

struct RunOptions {
  std::string scenario_path;  ///< empty: the embedded paper000 scenario
  RunOverrides overrides;
  std::string out_dir = "results/run";
  int domain = 0;
  std::optional<std::uint64_t> run_id;  ///< default: random
  std::optional<std::string> qos_file;
  std::optional<std::string> secure_dir;      ///< DDS-Security: a folder made by `skyfuse certs`
  std::optional<double> discovery_timeout_s;  ///< default: discovery_timeout_s() below
  double round_timeout_s = 10.0;              ///< a running node silent this long ends the run
  /// A lock-step round closes this long after its tick with what has arrived (nodes), and the
  /// harness records it at twice this plus 250 ms.
  double round_deadline_ms = 1000.0;
  LinkLoss loss;
  bool best_effort = false;
  NisGate gate;                        ///< the nodes' chi^2 gate on measurements (default: none)
  std::vector<StationEvent> kills;     ///< SIGKILL a station before a step's round
  std::vector<StationEvent> restarts;  ///< start a killed station again before a step's round
  std::string replay_path;  ///< stations replay measurements from this CSV instead of simulating
  bool external = false;    ///< stations and center are started elsewhere (by hand, compose)
  /// Real-time mode when > 0: nodes step on the wall clock at the scenario's dt, rounds close
  /// this many ms after they start.
  double realtime_deadline_ms = 0.0;
  bool verbose = false;
};

/// Seconds to wait until every process has joined: the option if given, else
/// default_discovery_timeout_s(stations).
double discovery_timeout_s(const RunOptions& options, int stations);

/// Tells the user on stderr when `stations` stations need larger socket buffers than the
/// kernel grants (transport::receive_buffer_warning); says nothing otherwise.
void warn_if_receive_buffers_too_small(int stations);

void add_run_command(CLI::App& app, RunOptions& options);
int run_run(const RunOptions& options);

/// One DDS run of `plan` with results written to options.out_dir; throws RunAborted on failure.
RunSummary execute_run(const RunOptions& options, const RunPlan& plan);

}  // namespace skyfuse::harness
