#pragma once
// `skyfuse run`: the system as it is meant to run - one process per station plus the fusion
// center, over DDS, driven in lock-step by this harness.

#include <CLI/App.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "run_report.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/sim/run_plan.hpp"

namespace skyfuse::harness {

struct RunOptions {
  /// What every node of the run is given (scenario, plan, domain, QoS, security, deadlines,
  /// loss, NIS gate): one contract with the nodes, passed on by options::to_arguments. The
  /// harness fills in per run what only it knows: the run id, the timeouts, the log level.
  /// round_deadline_ms also sets when the harness records a round (twice it plus 250 ms).
  options::NodeOptions node;
  std::string out_dir = "results/run";
  std::optional<std::uint64_t> run_id;        ///< default: random
  std::optional<double> discovery_timeout_s;  ///< default: discovery_timeout_s() below
  double round_timeout_s = 10.0;              ///< a running node silent this long ends the run
  std::vector<StationEvent> kills;            ///< SIGKILL a station before a step's round
  std::vector<StationEvent> restarts;  ///< start a killed station again before a step's round
  std::string replay_path;  ///< stations replay measurements from this CSV instead of simulating
  bool external = false;    ///< stations and center are started elsewhere (by hand, compose)
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
