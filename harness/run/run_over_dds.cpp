#include "run/run_over_dds.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "report/progress.hpp"
#include "run/kernel_counters.hpp"
#include "run/lockstep_driver.hpp"
#include "run/placement.hpp"
#include "run/run_nodes.hpp"
#include "skyfuse/transport/node_setup.hpp"
#include "skyfuse/transport/security_folder.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {
namespace {

using Clock = std::chrono::steady_clock;

// How long after the last round every node's FINISHED is waited for before it is worth a word.
constexpr std::chrono::seconds kFinishedWithin{5};

std::chrono::milliseconds seconds_to_ms(double s) {
  return std::chrono::milliseconds(std::llround(s * 1000.0));
}

std::uint64_t nanoseconds_since_epoch(std::chrono::system_clock::time_point t) {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count());
}

// The harness's own DDS participant for a run of `stations` placed by `placement`: the run's
// domain, QoS file, reliability, network, lease, discovery server and security identity.
transport::NodeConfig harness_node_config(const RunOptions& o, const Placement& placement,
                                          int stations) {
  transport::NodeConfig config;
  config.domain_id = o.node.domain;
  config.name = "skyfuse-harness";
  if (o.node.qos_file) config.qos_file = *o.node.qos_file;
  config.best_effort_data = o.node.best_effort;
  config.network = placement.harness();
  config.network.lease_s = options::lease_seconds(stations);
  config.serves_discovery = config.network.discovery_server.has_value();  // the nodes' server
  if (o.node.secure_dir) {
    config.security = transport::SecurityConfig{*o.node.secure_dir, transport::kHarnessIdentity};
  }
  return config;
}

// The kills and restarts `o` asks for before the round of `step`, told to `roster`: a killed
// station is not waited for, a restarted one is once it is ready again.
void apply_station_events(const RunOptions& o, std::uint64_t step, RunNodes& nodes,
                          NodeRoster& roster, std::chrono::milliseconds ready_timeout) {
  for (const StationEvent& e : o.kills) {
    if (e.step != step) continue;
    nodes.kill_station(e.station_id);
    roster.set_down(e.station_id, true);
    spdlog::info("killed station {} before step {}", e.station_id, step);
  }
  for (const StationEvent& e : o.restarts) {
    if (e.step != step) continue;
    nodes.restart_station(e.station_id, step);
    roster.wait_until_ready(e.station_id, ready_timeout);
    roster.set_down(e.station_id, false);
    spdlog::info("restarted station {} before step {}", e.station_id, step);
  }
}

// The rounds from the first to the last, or until one stops them (RunAborted, returned).
std::optional<RunAborted> drive_rounds(const RunOptions& o, RunKind& kind, RunNodes& nodes,
                                       std::chrono::system_clock::time_point epoch,
                                       std::chrono::milliseconds ready_timeout,
                                       Progress& progress) {
  const auto round_timeout = seconds_to_ms(o.round_timeout_s);
  try {
    if (o.node.realtime_deadline_ms > 0.0) {
      kind.run_realtime(epoch, round_timeout, [&] { progress.advance(); });
      return std::nullopt;
    }
    // Without loss, the first rounds of a connected network are complete.
    ConnectionCheck connection(!o.node.loss.enabled(), o.node.best_effort);
    for (int k = 0; k < kind.steps(); ++k) {
      apply_station_events(o, static_cast<std::uint64_t>(k), nodes, kind.roster(), ready_timeout);
      kind.run_lockstep_round(k, round_timeout, connection);
      progress.advance();
    }
    return std::nullopt;
  } catch (const RunAborted& e) {
    return e;
  }
}

}  // namespace

double discovery_timeout_s(const RunOptions& o, int stations) {
  return o.discovery_timeout_s.value_or(default_discovery_timeout_s(stations));
}

void run_over_dds(const RunOptions& o, RunKind& kind) {
  const std::vector<int> ids = kind.station_ids();
  check_before_start(o, ids, kind.steps());

  const std::filesystem::path scenario_file = write_run_scenario(o);
  const std::uint64_t run_id = o.run_id.value_or(fresh_run_id());
  const double discovery_timeout = discovery_timeout_s(o, kind.stations());
  const auto ready_timeout = seconds_to_ms(discovery_timeout);
  const Placement placement(o, kind.placement_exchange(), ids.size());
  // Process 0 is the center, then the stations in ascending id, --stations-per-process to a
  // process (a station restarts only when each has its own: Placement::check).
  RunNodes nodes(
      o, placement, ids,
      [&](const options::NetworkOptions& network) {
        options::NodeOptions child =
            node_options_for(o, network, scenario_file, run_id, discovery_timeout);
        kind.complete_node_options(child);
        return options::to_arguments(child);
      },
      kind.station_arguments());
  kind.open(harness_node_config(o, placement, kind.stations()), run_id, [&] { nodes.check(); });
  try {
    ProcessMeasures measured;
    measured.discovery = placement.discovery();
    nodes.start();
    const auto discovery_start = Clock::now();
    kind.roster().wait_until_joined(ready_timeout);
    measured.discovery_s = std::chrono::duration<double>(Clock::now() - discovery_start).count();
    // Endpoint discovery may go on after every node is ready (run/discovery_quiet.hpp).
    const QuietWait settled = nodes.wait_until_quiet();
    measured.settle_s = std::chrono::duration<double>(settled.waited).count();
    measured.settled_quiet = settled.quiet;

    Progress progress(kind.progress_label(), kind.steps());
    measured.realtime = o.node.realtime_deadline_ms > 0.0;
    const auto epoch = std::chrono::system_clock::now() +
                       (measured.realtime ? kRealtimeHeadStart : std::chrono::milliseconds::zero());
    measured.epoch_ns = nanoseconds_since_epoch(epoch);
    kind.begin_rounds(measured.epoch_ns);
    const KernelSnapshot before_rounds = nodes.kernel_snapshot();
    const auto start = Clock::now();
    // A run that stops once its rounds have begun keeps what it recorded: the nodes are
    // stopped as after the last round, and every file is written before the run is reported
    // as stopped (the kind's StoppedEarlyWith).
    measured.stopped = drive_rounds(o, kind, nodes, epoch, ready_timeout, progress);
    measured.rounds_s = std::chrono::duration<double>(Clock::now() - start).count();
    const KernelSnapshot after_rounds = nodes.kernel_snapshot();
    measured.node_peak_resident_mib = nodes.peak_resident_mib();
    progress.finish();

    const double rounds = std::max(kind.rounds_worked(), 1.0);
    if (before_rounds.udp_datagrams && after_rounds.udp_datagrams) {
      measured.datagrams_per_round =
          static_cast<double>(*after_rounds.udp_datagrams - *before_rounds.udp_datagrams) / rounds;
    }
    measured.cpu_ms_per_station_round = 1e3 * (after_rounds.cpu_s - before_rounds.cpu_s) /
                                        (static_cast<double>(kind.stations()) * rounds);
    // Nodes announce FINISHED after their last round and wait to be released; a run that
    // stopped early releases them at once.
    if (!measured.stopped && !kind.roster().wait_until_finished(kFinishedWithin)) {
      spdlog::warn("not every node announced FINISHED within {} s of the last round",
                   kFinishedWithin.count());
    }
    kind.roster().send_stop();
    nodes.finish(std::chrono::seconds(10), measured.stopped.has_value());
    measured.node_exits = nodes.exits();
    kind.end(measured, run_id);
  } catch (...) {
    kind.roster().send_stop();
    nodes.terminate();
    throw;
  }
}

int exit_status_of(const RunAborted& e) {
  // As a shell reports a process its signal ended (130 for Ctrl-C, 143 for SIGTERM), whatever
  // the signal made fail first.
  if (transport::shutdown_requested()) return 128 + transport::shutdown_signal();
  const bool stopped_early =
      e.cause() == StopCause::kFellBehind || e.cause() == StopCause::kRoundTimeout;
  return stopped_early ? kExitStoppedEarly : 1;
}

void check_station_events(const RunOptions& o, const std::vector<int>& participant_ids,
                          int run_steps) {
  const auto steps = static_cast<std::uint64_t>(run_steps);
  for (const auto* list : {&o.kills, &o.restarts}) {
    for (const StationEvent& e : *list) {
      const char* option = list == &o.kills ? "--kill" : "--restart";
      if (std::find(participant_ids.begin(), participant_ids.end(), e.station_id) ==
          participant_ids.end()) {
        throw std::invalid_argument(
            fmt::format("{} {}@{}: station {} does not take part in the run", option, e.station_id,
                        e.step, e.station_id));
      }
      if (e.step == 0 || e.step >= steps) {
        throw std::invalid_argument(fmt::format("{} {}@{}: the step must be in [1, {}]", option,
                                                e.station_id, e.step, steps - 1));
      }
    }
  }
  if ((!o.kills.empty()) && (o.external || o.node.realtime_deadline_ms > 0.0)) {
    throw std::invalid_argument("--kill/--restart: lock-step runs with started processes only");
  }
  for (int id : participant_ids) {
    std::vector<std::pair<std::uint64_t, bool>> events;  // step, is_kill
    for (const StationEvent& e : o.kills) {
      if (e.station_id == id) events.emplace_back(e.step, true);
    }
    for (const StationEvent& e : o.restarts) {
      if (e.station_id == id) events.emplace_back(e.step, false);
    }
    std::sort(events.begin(), events.end());
    bool up = true;
    for (const auto& [step, is_kill] : events) {
      if (is_kill != up) {
        throw std::invalid_argument(fmt::format(
            "--kill/--restart: station {} at step {}: {} (kill and restart must alternate, a "
            "restart later than its kill)",
            id, step, is_kill ? "is already down" : "is not down"));
      }
      up = !is_kill;
    }
  }
}

}  // namespace skyfuse::harness
