#include "run/picture_run.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string_view>
#include <vector>

#include "report/output_files.hpp"
#include "report/picture_live_source.hpp"
#include "report/picture_recording.hpp"
#include "report/picture_run_report.hpp"
#include "report/progress.hpp"
#include "run/child_processes.hpp"
#include "run/execute_run.hpp"
#include "run/kernel_counters.hpp"
#include "run/lockstep_driver.hpp"
#include "run/picture_driver.hpp"
#include "run/picture_frame.hpp"
#include "run/picture_round_check.hpp"
#include "run/placement.hpp"
#include "run/secure_start.hpp"
#include "run/station_groups.hpp"
#include "skyfuse/core/sorted_ids.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/sim/picture_run.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/security_folder.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {
namespace {

using namespace std::chrono_literals;

using Clock = std::chrono::steady_clock;
// Real time: step 0 begins this long after every node joined, so that the start tick reaches
// every node first (the single-target run's head start).
constexpr std::chrono::milliseconds kRealtimeHeadStart{1000};
// Real time: a round whose pictures have not all come this long after its scheduled end is
// handed over with those that did.
constexpr std::chrono::milliseconds kLateAfter{2000};

// What a run of many aircraft does not take yet, each with why; nothing if `o` is fine.
void refuse_what_a_picture_run_lacks(const RunOptions& o) {
  const auto refuse = [](const char* option, const char* why) {
    throw std::invalid_argument(
        fmt::format("{}: not for a run of many aircraft yet: {} (docs/multitarget.md says what "
                    "runs over DDS so far)",
                    option, why));
  };
  if (!o.replay_path.empty()) {
    refuse("--replay", "its stations' scans are not recorded to be replayed");
  }
  if (o.external) {
    refuse("--external",
           "the harness starts a picture run's processes itself (containers run one aircraft)");
  }
  if (o.node.refusion_lag != 0) refuse("--refusion-lag", "a picture re-fuses no late scan");
}

// One start of every process of the run.
PictureRunSummary run_picture_once(const RunOptions& o, const PicturePlan& plan) {
  const std::vector<int> ids = sorted_ascending(plan.participant_ids());
  check_station_events(o, ids, plan.scenario.steps);
  if (o.node.secure_dir) {  // every node's identity checked here: one message instead of M + 1
    transport::SecurityFolder{*o.node.secure_dir}.check(transport::run_identities(ids));
  }

  // The in-process twin first: what every peer's picture must equal, round by round.
  const TrafficTruth truth = build_traffic_truth(plan.scenario, o.node.traffic_file);
  // The nodes read the scenario's copy in the results folder: a recorded file it names relative
  // to itself is passed to them by its absolute path.
  const auto recorded = recorded_traffic_file(plan.scenario, o.node.traffic_file);
  const PictureRunResult twin =
      run_picture(plan.scenario, truth.targets, plan.stations, plan.mc_run);

  const std::filesystem::path out(o.out_dir);
  std::filesystem::create_directories(out);
  const std::filesystem::path scenario_file = std::filesystem::absolute(out / "scenario.yaml");
  write_file_atomically(scenario_file, read_scenario_text(o.node.scenario_path));
  const std::uint64_t run_id = o.run_id.value_or(fresh_run_id());
  const double discovery_timeout =
      o.discovery_timeout_s.value_or(default_discovery_timeout_s(plan.stations));

  // Discovery as for the flat exchange, whichever exchange the scans take: every station
  // hears every cluster's aggregator, and the lowest station's whole picture when peers part.
  ExchangeConfig everyone_meets = plan.scenario.exchange;
  everyone_meets.kind = ExchangeConfig::Kind::kFlat;
  const Placement placement(o, everyone_meets, ids.size());
  std::vector<int> nodes = ids;  // the center (0) first, then the stations ascending
  nodes.insert(nodes.begin(), kCenterNodeId);
  // The live stream listens before the nodes start, so that a client can be there for the
  // first round.
  std::unique_ptr<PictureLiveFeed> live;
  if (o.live) {
    live::LiveServer::Options server;
    server.address = o.live->address;
    server.port = o.live->port;
    if (const auto site = executable_dir() / "view"; std::filesystem::exists(site / "index.html")) {
      server.site_dir = site.string();
    }
    live =
        std::make_unique<PictureLiveFeed>(std::move(server), o.live_scene_hz, plan, truth.targets);
    fmt::print("live: ws://{0}:{1} (Foxglove), http://{0}:{1}/ (page)\n", o.live->address,
               live->port());
    std::fflush(stdout);
  }
  ChildProcesses children;
  PictureDriver driver(harness_node_config(o, placement, plan.stations), run_id, nodes, children);
  try {
    // One process per network namespace (a simulated host; -1: the harness's own), for the
    // kernel's UDP counters.
    std::map<int, pid_t> namespace_members{{-1, getpid()}};
    // Process 0 is the center, then the stations in ascending id, --stations-per-process to a
    // process (a station restarts only when each has its own: Placement::check): each with the
    // run's options, on its host.
    const StationGroups groups(ids.size(), static_cast<std::size_t>(o.stations_per_process));
    const auto spawn = [&](std::size_t process, std::vector<std::string> argv,
                           const std::string& name) {
      options::NodeOptions child = o.node;
      const auto [network, netns] = placement.of(process);
      child.network = network;
      if (child.secure_dir) {
        child.secure_dir = std::filesystem::absolute(*child.secure_dir).string();
      }
      child.scenario_path = scenario_file.string();
      if (recorded) child.traffic_file = std::filesystem::absolute(*recorded).string();
      child.run_id = run_id;
      child.overrides.stations = plan.stations;
      child.overrides.steps = plan.scenario.steps;
      child.overrides.mc_run = plan.mc_run;
      child.discovery_timeout_s = discovery_timeout;
      child.idle_timeout_s = std::max(30.0, 3.0 * o.round_timeout_s);
      child.log_level = o.verbose ? "info" : "warn";
      const std::vector<std::string> common = options::to_arguments(child);
      argv.insert(argv.end(), common.begin(), common.end());
      namespace_members.try_emplace(netns, children.spawn(name, argv, netns));
    };
    const auto spawn_stations = [&](std::size_t process, std::optional<int> rejoin_step) {
      const std::vector<int> group = groups.ids_of(process, ids);
      std::vector<std::string> argv = id_arguments(group);
      argv.insert(argv.begin(), (executable_dir() / "skyfuse-station").string());
      if (rejoin_step) {
        argv.push_back("--rejoin-at-step");
        argv.push_back(std::to_string(*rejoin_step));
      }
      spawn(process, std::move(argv), process_name(group));
    };
    const auto spawn_station = [&](int id, std::optional<int> rejoin_step) {
      spawn_stations(groups.process_of_id(id, ids), rejoin_step);
    };
    spawn(0, {(executable_dir() / "skyfuse-center").string()}, node_name(kCenterNodeId));
    for (std::size_t p = 1; p < groups.processes(); ++p) spawn_stations(p, std::nullopt);
    const auto discovery_start = Clock::now();
    driver.wait_until_joined(std::chrono::milliseconds(std::llround(discovery_timeout * 1e3)));
    // The kernel's counts over every process of the run, and every namespace's datagrams.
    const auto kernel_snapshot = [&] {
      std::vector<pid_t> processes = children.pids();
      processes.push_back(getpid());
      std::vector<pid_t> one_per_namespace;
      for (const auto& [netns, pid] : namespace_members) one_per_namespace.push_back(pid);
      return take_snapshot(processes, one_per_namespace);
    };
    const KernelSnapshot before_rounds = kernel_snapshot();

    PictureRunSummary summary;
    summary.scenario = plan.scenario.name;
    summary.stations = plan.stations;
    summary.exchange = std::string(to_string(plan.scenario.exchange.kind));
    if (plan.scenario.exchange.kind == ExchangeConfig::Kind::kTree) {
      summary.fanout = plan.scenario.exchange.fanout;
    }
    summary.steps = plan.scenario.steps;
    summary.stations_per_process = o.stations_per_process;
    summary.discovery_s = std::chrono::duration<double>(Clock::now() - discovery_start).count();
    Progress progress(fmt::format("picture M={}", plan.stations), plan.scenario.steps);
    const auto round_timeout = std::chrono::milliseconds(std::llround(o.round_timeout_s * 1e3));
    const auto start = Clock::now();
    PictureRoundCheck check(plan, truth.targets, twin, summary);
    const bool realtime = o.node.realtime_deadline_ms > 0.0;
    const auto epoch = std::chrono::system_clock::now() + (realtime ? kRealtimeHeadStart : 0s);
    const auto epoch_ns = static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(epoch.time_since_epoch()).count());
    std::optional<PictureRecording> recording;
    if (!o.record_path.empty()) recording.emplace(o.record_path, plan, epoch_ns);
    if (live) live->set_epoch_ns(epoch_ns);
    // `latency`: lock-step, from the tick to the last picture; real time, from the round's
    // scheduled end to its hand-over.
    // Without loss or a station down, the first round of a lock-step run fuses every scan at
    // every node in a connected network; if none of the first connection_rounds_of(o) does,
    // some pair of processes never matched (seen with secure discovery) and every round would
    // wait for its deadline: say so at once.
    const int connection_rounds = connection_rounds_of(o);
    bool checking_connection = !realtime && !o.node.loss.enabled() &&
                               std::none_of(o.kills.begin(), o.kills.end(),
                                            [](const StationEvent& e) { return e.step == 0; });
    const auto take_round = [&](int k, const std::vector<wire::PictureRound>& rounds,
                                std::chrono::duration<double, std::milli> latency) {
      if (checking_connection) {
        std::vector<std::string> short_of;
        for (const wire::PictureRound& r : rounds) {
          if (r.scans_fused() < static_cast<std::uint32_t>(plan.stations)) {
            short_of.push_back(fmt::format("{}: {} of {} scans", node_name(r.source_id()),
                                           r.scans_fused(), plan.stations));
          }
        }
        if (short_of.empty()) {
          checking_connection = false;
        } else if (k + 1 >= connection_rounds) {
          throw RunAborted(fmt::format("{}, the network is not fully connected: {}",
                                       connection_rounds == 1
                                           ? std::string("round 0 incomplete")
                                           : fmt::format("rounds 0-{} all incomplete", k),
                                       fmt::join(short_of, ", ")));
        }
      }
      const PictureStep* scored = check.add(k, rounds);
      if ((recording || live) && scored != nullptr) {
        PictureFrame frame = picture_frame(k, rounds, nodes, *scored);
        frame.latency_ms = latency.count();
        if (live) live->offer(frame);
        if (recording) {
          add_scene(plan, truth.targets, frame);
          recording->add(frame);
        }
      }
      progress.advance();
    };
    if (realtime) {
      driver.run_realtime(
          plan.scenario.steps, plan.scenario.time_step_s, epoch, kLateAfter,
          [&](int k, std::vector<wire::PictureRound> rounds) {
            const auto scheduled_end =
                epoch + std::chrono::duration_cast<std::chrono::system_clock::duration>(
                            std::chrono::duration<double>((k + 1) * plan.scenario.time_step_s));
            take_round(k, rounds, std::chrono::system_clock::now() - scheduled_end);
          });
    } else {
      for (int k = 0; k < plan.scenario.steps; ++k) {
        for (const StationEvent& e : o.kills) {
          if (e.step != static_cast<std::uint64_t>(k)) continue;
          children.kill_now(node_name(e.station_id));
          driver.set_down(e.station_id, true);
          spdlog::info("killed station {} before step {}", e.station_id, k);
        }
        for (const StationEvent& e : o.restarts) {
          if (e.step != static_cast<std::uint64_t>(k)) continue;
          spawn_station(e.station_id, k);
          driver.wait_until_ready(e.station_id,
                                  std::chrono::milliseconds(std::llround(discovery_timeout * 1e3)));
          driver.set_down(e.station_id, false);
          spdlog::info("restarted station {} before step {}", e.station_id, k);
        }
        const auto tick = Clock::now();
        const auto rounds = driver.run_round(static_cast<std::uint32_t>(k), round_timeout);
        take_round(k, rounds, Clock::now() - tick);
      }
    }
    const KernelSnapshot after_rounds = kernel_snapshot();
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const double rounds = plan.scenario.steps;
    if (before_rounds.udp_datagrams && after_rounds.udp_datagrams) {
      summary.datagrams_per_round =
          static_cast<double>(*after_rounds.udp_datagrams - *before_rounds.udp_datagrams) / rounds;
    }
    summary.cpu_ms_per_station_round =
        1e3 * (after_rounds.cpu_s - before_rounds.cpu_s) / (plan.stations * rounds);
    summary.rounds_per_s = plan.scenario.steps / seconds;
    summary.loss = o.node.loss.enabled();
    summary.faults = summary.loss || !o.kills.empty();
    summary.realtime = o.node.realtime_deadline_ms > 0.0;
    summary.gospa_mean = check.gospa_mean();
    summary.in_process_gospa_mean = twin.score.gospa_mean;
    for (const auto& [id, finished] : driver.wait_finished(std::chrono::seconds(5))) {
      if (id != kCenterNodeId) summary.resyncs += finished.resyncs;
      summary.lost += finished.lost;
      summary.dropped_by_node[id] = finished.dropped;
    }
    driver.release();
    if (!children.wait_all(std::chrono::seconds(10))) {
      spdlog::warn("station processes still running 10 s after the run; stopping them");
      children.terminate_all(std::chrono::seconds(2));
    }

    write_file_atomically(out / "picture_rounds.csv", check.csv());
    const std::string summary_json = picture_run_json(summary, run_id, twin);
    write_file_atomically(out / "summary.json", summary_json + "\n");
    if (recording) recording->finish(summary_json, plan.scenario.steps);
    if (live) {
      live->finish(summary_json);
      const live::LiveServer::Stats stats = live->stats();
      fmt::print("live: {} message(s) sent, {} client(s) connected at the end\n", stats.frames_sent,
                 stats.clients);
      if (live->rounds_dropped() > 0) {
        spdlog::warn("live: {} round(s) not streamed: the stream fell more than {} rounds behind",
                     live->rounds_dropped(), PictureLiveFeed::kMaxWaitingRounds);
      }
    }
    return summary;
  } catch (...) {
    children.terminate_all(std::chrono::seconds(2));
    throw;
  }
}

}  // namespace

PictureRunSummary execute_picture_run(const RunOptions& o, const Scenario& scenario) {
  refuse_what_a_picture_run_lacks(o);
  // A secure start on Fast DDS 2.9 sometimes stalls (secure_start.hpp).
  const PicturePlan plan = make_picture_plan(scenario, o.node.overrides);
  return with_secure_restarts(
      o, discovery_timeout_s(o, plan.stations),
      [&](const RunOptions& attempt) { return run_picture_once(attempt, plan); });
}

}  // namespace skyfuse::harness
