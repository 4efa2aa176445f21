#include "run/execute_run.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <thread>

#include "report/output_files.hpp"
#include "report/progress.hpp"
#include "report/run_live_source.hpp"
#include "report/run_recording.hpp"
#include "run/child_processes.hpp"
#include "run/discovery_quiet.hpp"
#include "run/kernel_counters.hpp"
#include "run/lockstep_driver.hpp"
#include "run/placement.hpp"
#include "run/secure_start.hpp"
#include "run/station_groups.hpp"
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

// The longest the rounds wait for discovery to go quiet after every node joined.
constexpr std::chrono::seconds kSettleLimit{60};

// How long the first rounds of a lock-step run may all be incomplete before the network counts
// as not fully connected (with at least connection_rounds_of() rounds).
constexpr std::chrono::seconds kConnectionGrace{60};

// Real time: step 0 begins this long after every node joined, so that the start tick reaches
// every node and discovery's last exchanges are over. At M = 64 both cores stay busy until
// 0.2-0.3 s after the last node joins; with 300 ms, the first rounds ran beside them and came
// late.
constexpr std::chrono::milliseconds kRealtimeHeadStart{1000};

// The embedded default, or the file: the nodes read exactly this text from the results folder.
std::string scenario_text(const std::string& path) {
  return path.empty() ? std::string(default_scenario_yaml()) : read_scenario_text(path);
}

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
  options::NodeOptions child = o.node;
  child.network = network;
  child.scenario_path = scenario_file.string();
  child.run_id = run_id;
  child.overrides = {plan.stations, plan.scenario.steps,         plan.speed_mps * 3.6,
                     plan.mc_run,   plan.scenario.exchange.kind, plan.scenario.exchange.fanout,
                     std::nullopt,   // one target: no aircraft to count
                     std::nullopt};  // nor anything to associate
  child.discovery_timeout_s = discovery_timeout_s(o, plan.stations);
  child.idle_timeout_s = std::max(30.0, 3.0 * o.round_timeout_s);
  child.log_level = o.verbose ? "info" : "warn";
  if (child.secure_dir) child.secure_dir = std::filesystem::absolute(*child.secure_dir).string();
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
template <typename SpawnStation>
void run_lockstep_rounds(const RunOptions& o, const RunPlan& plan, LockstepDriver& driver,
                         ChildProcesses& children, RunRecorder& recorder, LiveFeed* live,
                         Progress& progress, const SpawnStation& spawn_station) {
  const auto round_timeout = seconds_to_ms(o.round_timeout_s);
  const auto close_after =
      std::chrono::milliseconds(std::llround(2.0 * o.node.round_deadline_ms + 250.0));
  const std::size_t stations = plan.participant_ids().size();
  // How many of the first rounds may all be incomplete before the network counts as broken.
  const int connection_rounds = connection_rounds_of(o);
  bool checking_connection = true;
  const auto first_round = std::chrono::steady_clock::now();
  for (int k = 0; k < plan.scenario.steps; ++k) {
    const auto step = static_cast<std::uint64_t>(k);
    for (const StationEvent& e : o.kills) {
      if (e.step != step) continue;
      children.kill_now(node_name(e.station_id));
      driver.set_down(e.station_id, true);
      spdlog::info("killed station {} before step {}", e.station_id, step);
    }
    for (const StationEvent& e : o.restarts) {
      if (e.step != step) continue;
      spawn_station(e.station_id, step);
      driver.wait_until_ready(e.station_id, seconds_to_ms(discovery_timeout_s(o, plan.stations)));
      driver.set_down(e.station_id, false);
      spdlog::info("restarted station {} before step {}", e.station_id, step);
    }
    RoundRecord round = driver.run_round(step, close_after, round_timeout);
    // Without loss, the first rounds are complete in a connected network; if none is, some
    // pair of processes never matched (seen with secure discovery), and every round would
    // wait for its deadline. Better to say so at once. With reliable samples one round
    // tells; best effort may lose a sample of round 0 while the sockets still fill (seen at
    // M = 64 on a slow host), which is a loss, not a broken network: it gets a few rounds.
    // And a large run's first rounds may run beside the last of discovery: at M = 256 in 17
    // processes the endpoints' announcements went on for the first rounds (66 000 datagrams
    // a round), and the clusters' sums came after their stage had closed. So the first
    // rounds may all be incomplete for kConnectionGrace too.
    if (checking_connection && !o.node.loss.enabled()) {
      if (const auto missing = missing_from(round, stations)) {
        if (k + 1 >= connection_rounds &&
            std::chrono::steady_clock::now() - first_round >= kConnectionGrace) {
          throw RunAborted(fmt::format("{}, the network is not fully connected: {}",
                                       connection_rounds == 1
                                           ? std::string("round 0 incomplete")
                                           : fmt::format("rounds 0-{} all incomplete", k),
                                       *missing));
        }
      } else {
        checking_connection = false;
      }
    }
    if (live) live->offer(round);
    recorder.add(std::move(round));
    progress.advance();
  }
}

RunSummary run_once(const RunOptions& o, const RunPlan& plan) {
  // Refusals first: a refused command leaves an earlier run's folder as it was.
  check_station_events(o, plan.participant_ids(), plan.scenario.steps);
  Placement::check(o, static_cast<std::size_t>(plan.stations));
  const std::vector<int> ids = plan.participant_ids();
  if (o.node.secure_dir) {  // every node's identity checked here: one message instead of M + 1
    transport::SecurityFolder{*o.node.secure_dir}.check(transport::run_identities(ids));
  }

  const std::filesystem::path out(o.out_dir);
  std::filesystem::create_directories(out);
  // The processes read the very file saved with the results: what ran is what is on disk.
  const std::filesystem::path scenario_file = std::filesystem::absolute(out / "scenario.yaml");
  write_file_atomically(scenario_file, scenario_text(o.node.scenario_path));
  const std::uint64_t run_id = o.run_id.value_or(fresh_run_id());

  ChildProcesses children;
  const auto check = [&] {
    if (transport::shutdown_requested()) {
      throw RunAborted(fmt::format("interrupted by signal {}", transport::shutdown_signal()),
                       StopCause::kInterrupted);
    }
    for (const ChildExit& e : children.poll()) {
      if (!e.success()) throw RunAborted(e.describe(), StopCause::kNodeFailed);
    }
  };
  const Placement placement(o, plan.scenario.exchange, ids.size());
  const transport::NodeConfig config = harness_node_config(o, placement, plan.stations);
  const TrackShape shape{find_motion_model(plan.scenario.filter.motion_model.kind)->state_dim,
                         find_filter(plan.scenario.filter)->mode_names.size()};
  LockstepDriver driver(config, run_id, plan.participants(), shape, check);

  // One process per network namespace, for the kernel's UDP counters (-1: the harness's own).
  std::map<int, pid_t> namespace_members{{-1, getpid()}};
  const auto kernel_snapshot = [&] {
    std::vector<pid_t> processes = children.pids();
    processes.push_back(getpid());
    std::vector<pid_t> one_per_namespace;
    for (const auto& [netns, pid] : namespace_members) one_per_namespace.push_back(pid);
    return take_snapshot(processes, one_per_namespace);
  };

  try {
    // Process 0 is the center, then the stations in ascending id, --stations-per-process to a
    // process (a station restarts only when each has its own: Placement::check).
    const StationGroups groups(ids.size(), static_cast<std::size_t>(o.stations_per_process));
    const auto spawn_process = [&](std::size_t process, std::optional<std::uint64_t> rejoin_step) {
      const std::vector<int> group = groups.ids_of(process, ids);
      const auto [network, netns] = placement.of(process);
      const std::vector<std::string> common =
          node_arguments(o, plan, run_id, scenario_file, network);
      std::vector<std::string> station{(executable_dir() / "skyfuse-station").string()};
      const std::vector<std::string> id_args = id_arguments(group);
      station.insert(station.end(), id_args.begin(), id_args.end());
      station.insert(station.end(), common.begin(), common.end());
      if (!o.replay_path.empty()) {
        station.push_back("--replay");
        station.push_back(std::filesystem::absolute(o.replay_path).string());
      }
      if (rejoin_step) {
        station.push_back("--rejoin-at-step");
        station.push_back(std::to_string(*rejoin_step));
      }
      namespace_members.try_emplace(netns, children.spawn(process_name(group), station, netns));
    };
    const auto spawn_station = [&](int id, std::optional<std::uint64_t> rejoin_step) {
      spawn_process(groups.process_of_id(id, ids), rejoin_step);
    };
    RunRecorder recorder(plan, ids, o.restarts);
    // The live stream listens before the nodes start, so that a client can be there for the
    // first round.
    std::unique_ptr<LiveFeed> live;
    if (o.live) {
      live::LiveServer::Options server;
      server.address = o.live->address;
      server.port = o.live->port;
      if (const auto site = executable_dir() / "view";
          std::filesystem::exists(site / "index.html")) {
        server.site_dir = site.string();
      }
      live = std::make_unique<LiveFeed>(std::move(server), o.live_scene_hz, recorder);
      fmt::print("live: ws://{0}:{1} (Foxglove), http://{0}:{1}/ (page)\n", o.live->address,
                 live->port());
      std::fflush(stdout);
    }
    if (!o.external) {
      const auto [network, netns] = placement.of(0);
      const std::vector<std::string> common =
          node_arguments(o, plan, run_id, scenario_file, network);
      std::vector<std::string> center{(executable_dir() / "skyfuse-center").string()};
      center.insert(center.end(), common.begin(), common.end());
      namespace_members.try_emplace(netns, children.spawn(node_name(kCenterNodeId), center, netns));
      for (std::size_t p = 1; p < groups.processes(); ++p) spawn_process(p, std::nullopt);
    }
    const auto discovery =
        driver.wait_until_joined(seconds_to_ms(discovery_timeout_s(o, plan.stations)));
    // Endpoint discovery may go on after every node is ready (run/discovery_quiet.hpp).
    const QuietWait settled = wait_until_quiet(
        [&] {
          std::vector<pid_t> processes = children.pids();
          processes.push_back(getpid());
          return std::optional<double>(take_snapshot(processes, {}).cpu_s);
        },
        quiet_cores(groups.processes() + 1), kSettleLimit,
        [&] {
          check();
          return true;
        });

    Progress progress(fmt::format("run M={} {:.0f} km/h", plan.stations, plan.speed_mps * 3.6),
                      plan.scenario.steps);
    const auto round_timeout = seconds_to_ms(o.round_timeout_s);
    const KernelSnapshot before_rounds = kernel_snapshot();
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
        run_lockstep_rounds(o, plan, driver, children, recorder, live.get(), progress,
                            spawn_station);
      }
    } catch (const RunAborted& e) {
      stopped = e;
    }
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    const KernelSnapshot after_rounds = kernel_snapshot();
    std::uint64_t node_peak_kib = 0;
    for (pid_t pid : children.pids()) {
      node_peak_kib = std::max(node_peak_kib, peak_resident_kib(pid).value_or(0));
    }
    progress.finish();

    // Nodes announce FINISHED after their last track and wait to be released; anything else
    // is worth a word. A run that stopped early releases them at once (the stop tick).
    if (!stopped && !driver.wait_until_finished(std::chrono::seconds(5))) {
      spdlog::warn("not every node announced FINISHED within 5 s of the last step");
    }
    driver.stop();
    if (!children.wait_all(std::chrono::seconds(5))) {
      spdlog::warn("{} node process(es) still running after the {}; terminating", children.alive(),
                   stopped ? "run stopped" : "last step");
    }
    children.terminate_all(std::chrono::seconds(2));
    // A node that fails during the run ends it (check() above), so these exits came after
    // every round was recorded (nodes leave without their participant's goodbye so that
    // Fast DDS's teardown race cannot abort them: transport/node_presence.hpp).
    for (const ChildExit& e : children.exited()) {
      if (!e.success()) {
        spdlog::warn("{} after the {}; every round is recorded", e.describe(),
                     stopped ? "run stopped" : "last round");
      }
    }

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
    summary.node_peak_resident_mib = static_cast<double>(node_peak_kib) / 1024.0;
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
    for (const ChildExit& e : children.exited()) summary.node_exits[e.name] = e.outcome();
    summary.host_verdict = host_verdict(summary, plan.scenario.time_step_s, cpu_model(),
                                        std::thread::hardware_concurrency());
    recorder.write(out, summary, run_id);
    const std::string summary_json = recorder.summary_json(summary, run_id);
    if (live) {
      live->finish(summary_json);
      const live::LiveServer::Stats stats = live->stats();
      fmt::print("live: {} message(s) sent, {} client(s) connected at the end\n", stats.frames_sent,
                 stats.clients);
      if (const auto dropped = stats.clients_dropped; dropped > 0) {
        fmt::print("live: {} client(s) dropped for falling behind\n", dropped);
      }
      if (live->rounds_dropped() > 0) {
        spdlog::warn("live: {} round(s) not streamed: the stream fell more than {} rounds behind",
                     live->rounds_dropped(), LiveFeed::kMaxWaitingRounds);
      }
    }
    if (!o.record_path.empty()) {
      write_recording(recorder, summary_json, o.record_path, wall_clock_ns(wall_start));
    }
    if (stopped) throw RunStoppedEarly(*stopped, std::move(summary));
    return summary;
  } catch (...) {
    driver.stop();
    children.terminate_all(std::chrono::seconds(2));
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
  return plan_from(scenario_text(o.node.scenario_path),
                   o.node.scenario_path.empty() ? "<embedded paper000.yaml>" : o.node.scenario_path,
                   o.node);
}

}  // namespace skyfuse::harness
