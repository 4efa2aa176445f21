#include "run/execute_run.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <thread>

#include "report/live_serving.hpp"
#include "report/output_files.hpp"
#include "report/progress.hpp"
#include "report/run_live_source.hpp"
#include "report/run_recording.hpp"
#include "run/connection_check.hpp"
#include "run/kernel_counters.hpp"
#include "run/lockstep_driver.hpp"
#include "run/placement.hpp"
#include "run/run_nodes.hpp"
#include "run/secure_start.hpp"
#include "skyfuse/options/filter_options.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/registry/filter_info.hpp"
#include "skyfuse/registry/part_info.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/node_setup.hpp"
#include "skyfuse/transport/qos.hpp"
#include "skyfuse/transport/security_folder.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {

double discovery_timeout_s(const RunOptions& o, int stations) {
  return o.discovery_timeout_s.value_or(default_discovery_timeout_s(stations));
}

void warn_if_receive_buffers_too_small(int stations) {
  if (const auto warning = transport::receive_buffer_warning(stations)) {
    fmt::print(stderr, "skyfuse: warning: {}\n", *warning);
  }
}

namespace {

using Clock = std::chrono::steady_clock;

RunPlan plan_from(const std::string& text, const std::string& source,
                  const options::NodeOptions& node) {
  RunPlan plan = make_run_plan(parse_scenario(text, source), node.overrides);
  // Refused here, before any process starts, rather than by each node.
  options::settle_exchange(plan.scenario, node);
  return plan;
}

// The arguments every node gets, so that it builds the same plan as the harness: the run's
// node options with what the harness decides for this run filled in.
std::vector<std::string> node_arguments(const RunOptions& o, const RunPlan& plan,
                                        std::uint64_t run_id,
                                        const std::filesystem::path& scenario_file,
                                        const options::NetworkOptions& network) {
  options::NodeOptions child =
      node_options_for(o, network, scenario_file, run_id, discovery_timeout_s(o, plan.stations));
  child.overrides = {plan.stations, plan.scenario.steps,         plan.speed_mps * 3.6,
                     plan.mc_run,   plan.scenario.exchange.kind, plan.scenario.exchange.fanout,
                     std::nullopt,   // one target: no aircraft to count
                     std::nullopt};  // nor anything to associate
  return options::to_arguments(child);
}

// Nanoseconds since the Unix epoch: a recording's and a live stream's log times.
std::uint64_t wall_clock_ns(
    std::chrono::system_clock::time_point t = std::chrono::system_clock::now()) {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count());
}

std::chrono::milliseconds seconds_to_ms(double s) {
  return std::chrono::milliseconds(static_cast<long>(std::llround(s * 1000.0)));
}

// What is missing from a round in which every node should have delivered and every peer fused
// every station: nothing, or a description.
std::optional<std::string> missing_from(const RoundRecord& r, std::size_t stations) {
  std::vector<std::string> short_of;
  const auto check = [&](const std::optional<ReceivedTrack>& t, const std::string& who) {
    if (!t) {
      short_of.push_back(who + ": no track");
    } else if (t->contributors.size() != stations) {
      short_of.push_back(
          fmt::format("{}: {} of {} stations", who, t->contributors.size(), stations));
    }
  };
  if (!r.central) short_of.push_back("center: no track");  // its stack may leave out gated ones
  for (std::size_t i = 0; i < r.peers.size(); ++i)
    check(r.peers[i], fmt::format("peer #{}", i + 1));
  if (short_of.empty()) return std::nullopt;
  return fmt::format("{}", fmt::join(short_of, ", "));
}

// The lock-step rounds: kills and restarts before their step's round, each round recorded
// (and streamed) as it closes.
void run_lockstep_rounds(const RunOptions& o, const RunPlan& plan, LockstepDriver& driver,
                         RunNodes& nodes, RunRecorder& recorder, LiveFeed* live,
                         Progress& progress) {
  const auto round_timeout = seconds_to_ms(o.round_timeout_s);
  const auto close_after =
      std::chrono::milliseconds(std::llround(2.0 * o.node.round_deadline_ms + 250.0));
  const std::size_t stations = plan.participant_ids().size();
  ConnectionCheck connection(!o.node.loss.enabled(), o.node.best_effort);
  for (int k = 0; k < plan.scenario.steps; ++k) {
    const auto step = static_cast<std::uint64_t>(k);
    apply_station_events(o, step, nodes, driver,
                         seconds_to_ms(discovery_timeout_s(o, plan.stations)));
    RoundRecord round = driver.run_round(step, close_after, round_timeout);
    connection.take(k, missing_from(round, stations));
    if (live) live->offer(round);
    recorder.add(std::move(round));
    progress.advance();
  }
}

RunSummary run_once(const RunOptions& o, const RunPlan& plan) {
  const std::vector<int> ids = plan.participant_ids();
  check_before_start(o, ids, plan.scenario.steps);

  const std::filesystem::path out(o.out_dir);
  const std::filesystem::path scenario_file = write_run_scenario(o);
  const std::uint64_t run_id = o.run_id.value_or(fresh_run_id());

  const Placement placement(o, plan.scenario.exchange, ids.size());
  const transport::NodeConfig config = harness_node_config(o, placement, plan.stations);
  const TrackShape shape{find_motion_model(plan.scenario.filter.motion_model.kind)->state_dim,
                         find_filter(plan.scenario.filter)->mode_names.size()};
  std::vector<std::string> station_extra;
  if (!o.replay_path.empty()) {
    station_extra = {"--replay", std::filesystem::absolute(o.replay_path).string()};
  }
  // Process 0 is the center, then the stations in ascending id, --stations-per-process to a
  // process (a station restarts only when each has its own: Placement::check).
  RunNodes nodes(
      o, placement, ids,
      [&](const options::NetworkOptions& network) {
        return node_arguments(o, plan, run_id, scenario_file, network);
      },
      std::move(station_extra));
  LockstepDriver driver(config, run_id, plan.participants(), shape, [&] { nodes.check(); });

  try {
    RunRecorder recorder(plan, ids, o.restarts);
    // The live stream listens before the nodes start, so that a client can be there for the
    // first round.
    std::unique_ptr<LiveFeed> live;
    if (o.live) {
      live = std::make_unique<LiveFeed>(live_server_options(*o.live), o.live_scene_hz, recorder);
      announce_live(*o.live, live->port());
    }
    nodes.start();
    const auto discovery =
        driver.wait_until_joined(seconds_to_ms(discovery_timeout_s(o, plan.stations)));
    // Endpoint discovery may go on after every node is ready (run/discovery_quiet.hpp).
    const QuietWait settled = nodes.wait_until_quiet();

    Progress progress(fmt::format("run M={} {:.0f} km/h", plan.stations, plan.speed_mps * 3.6),
                      plan.scenario.steps);
    const auto round_timeout = seconds_to_ms(o.round_timeout_s);
    const KernelSnapshot before_rounds = nodes.kernel_snapshot();
    const auto start = Clock::now();
    const auto wall_start = std::chrono::system_clock::now();
    if (live) live->set_epoch_ns(wall_clock_ns(wall_start));
    const bool realtime = o.node.realtime_deadline_ms > 0.0;
    // A run that stops once its rounds have begun keeps what it recorded: the nodes are stopped
    // below as after the last round, and every file is written before the run is reported as
    // stopped (RunStoppedEarly).
    std::optional<RunAborted> stopped;
    try {
      if (realtime) {
        const auto epoch = std::chrono::system_clock::now() + kRealtimeHeadStart;
        driver.run_realtime(plan.scenario.steps, plan.scenario.time_step_s, epoch, round_timeout,
                            [&](RoundRecord r) {
                              if (live) live->offer(r);
                              recorder.add(std::move(r));
                              progress.advance();
                            });
      } else {
        run_lockstep_rounds(o, plan, driver, nodes, recorder, live.get(), progress);
      }
    } catch (const RunAborted& e) {
      stopped = e;
    }
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    const KernelSnapshot after_rounds = nodes.kernel_snapshot();
    const double node_peak_mib = nodes.peak_resident_mib();
    progress.finish();

    // Nodes announce FINISHED after their last track and wait to be released; anything else
    // is worth a word. A run that stopped early releases them at once (the stop tick).
    if (!stopped && !driver.wait_until_finished(std::chrono::seconds(5))) {
      spdlog::warn("not every node announced FINISHED within 5 s of the last step");
    }
    driver.stop();
    nodes.finish(std::chrono::seconds(5), stopped.has_value());

    RunSummary summary =
        recorder.summarise(std::chrono::duration<double>(discovery).count(), elapsed);
    summary.realtime_deadline_ms = o.node.realtime_deadline_ms;
    if (stopped) {
      summary.stop_cause = stopped->cause();
      summary.end_detail = stopped->what();
    }
    // The rounds the nodes worked on: those recorded, or in real time as far as any node got.
    double rounds_worked = summary.steps;
    if (realtime) {
      const LockstepDriver::RealtimeProgress reached = driver.realtime_progress();
      summary.realtime_steps_scheduled = reached.steps_scheduled;
      summary.realtime_steps_reached = reached.steps_reached;
      if (stopped) summary.realtime_behind_s = reached.behind_s;
      rounds_worked = std::max(rounds_worked, static_cast<double>(reached.steps_reached));
    }
    rounds_worked = std::max(rounds_worked, 1.0);
    if (before_rounds.udp_datagrams && after_rounds.udp_datagrams) {
      summary.datagrams_per_round =
          static_cast<double>(*after_rounds.udp_datagrams - *before_rounds.udp_datagrams) /
          rounds_worked;
    }
    summary.cpu_ms_per_station_round = 1e3 * (after_rounds.cpu_s - before_rounds.cpu_s) /
                                       (static_cast<double>(plan.stations) * rounds_worked);
    summary.node_peak_resident_mib = node_peak_mib;
    summary.node_counts = driver.finished_counts();
    recorder.set_refusals_after_run(
        driver.take_refusals(static_cast<std::uint64_t>(plan.scenario.steps)));
    summary.round_deadline_ms = o.node.round_deadline_ms;
    summary.loss = o.node.loss;
    summary.best_effort = o.node.best_effort;
    summary.hosts = o.hosts;
    summary.stations_per_process = o.stations_per_process;
    summary.refusion_lag = o.node.refusion_lag;
    recorder.set_settled(driver.settled_tracks());
    summary.settled = recorder.summarise_settled();
    summary.discovery = placement.discovery();
    summary.settle_s = std::chrono::duration<double>(settled.waited).count();
    summary.settled_quiet = settled.quiet;
    summary.node_exits = nodes.exits();
    summary.host_verdict = host_verdict(summary, plan.scenario.time_step_s, cpu_model(),
                                        std::thread::hardware_concurrency());
    recorder.write(out, summary, run_id);
    const std::string summary_json = recorder.summary_json(summary, run_id);
    if (live) finish_live(*live, summary_json);
    if (!o.record_path.empty()) {
      write_recording(recorder, summary_json, o.record_path, wall_clock_ns(wall_start));
    }
    if (stopped) {
      std::string verdict = summary.host_verdict;
      throw StoppedEarlyWith<RunSummary>(*stopped, std::move(summary), std::move(verdict));
    }
    return summary;
  } catch (...) {
    driver.stop();
    nodes.terminate();
    throw;
  }
}

}  // namespace

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

RunSummary execute_run(const RunOptions& o, const RunPlan& plan) {
  // A secure start on Fast DDS 2.9 sometimes stalls (secure_start.hpp).
  return with_secure_restarts(o, discovery_timeout_s(o, plan.stations),
                              [&](const RunOptions& attempt) { return run_once(attempt, plan); });
}

RunPlan load_run_plan(const RunOptions& o) {
  return plan_from(run_scenario_text(o),
                   o.node.scenario_path.empty() ? "<embedded paper000.yaml>" : o.node.scenario_path,
                   o.node);
}

}  // namespace skyfuse::harness
