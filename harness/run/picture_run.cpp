#include "run/picture_run.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "report/live_serving.hpp"
#include "report/output_files.hpp"
#include "report/picture_live_source.hpp"
#include "report/picture_recording.hpp"
#include "report/picture_run_report.hpp"
#include "report/progress.hpp"
#include "run/connection_check.hpp"
#include "run/execute_run.hpp"
#include "run/kernel_counters.hpp"
#include "run/picture_driver.hpp"
#include "run/picture_frame.hpp"
#include "run/picture_round_check.hpp"
#include "run/placement.hpp"
#include "run/run_nodes.hpp"
#include "run/secure_start.hpp"
#include "skyfuse/core/sorted_ids.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/sim/picture_run.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"
#include "skyfuse/transport/dds_node.hpp"

namespace skyfuse::harness {
namespace {

using namespace std::chrono_literals;

using Clock = std::chrono::steady_clock;
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
  if (o.node.delay.enabled()) {
    refuse(o.node.delay.delay_ms > 0.0 ? "--link-delay-ms" : "--link-jitter-ms",
           "the picture's exchange holds no scan back on a simulated link");
  }
  if (o.node.gate.enabled()) {
    refuse("--nis-gate",
           "a picture gates each (track, detection) pair by its tracker's own chi^2 gate "
           "(the scenario's tracker.gate_probability)");
  }
}

// What round k's pictures lack: nothing when every node fused every station's scan, else
// which fused how many.
std::optional<std::string> scans_missing(const std::vector<wire::PictureRound>& rounds,
                                         int stations) {
  std::vector<std::string> short_of;
  for (const wire::PictureRound& r : rounds) {
    if (r.scans_fused() < static_cast<std::uint32_t>(stations)) {
      short_of.push_back(
          fmt::format("{}: {} of {} scans", node_name(r.source_id()), r.scans_fused(), stations));
    }
  }
  if (short_of.empty()) return std::nullopt;
  return fmt::format("{}", fmt::join(short_of, ", "));
}

// One start of every process of the run.
PictureRunSummary run_picture_once(const RunOptions& o, const PicturePlan& plan) {
  const std::vector<int> ids = sorted_ascending(plan.participant_ids());
  check_before_start(o, ids, plan.scenario.steps);

  // The in-process twin first: what every peer's picture must equal, round by round.
  const TrafficTruth truth = build_traffic_truth(plan.scenario, o.node.traffic_file);
  // The nodes read the scenario's copy in the results folder: a recorded file it names relative
  // to itself is passed to them by its absolute path.
  const auto recorded = recorded_traffic_file(plan.scenario, o.node.traffic_file);
  const PictureRunResult twin =
      run_picture(plan.scenario, truth.targets, plan.stations, plan.mc_run);

  const std::filesystem::path out(o.out_dir);
  const std::filesystem::path scenario_file = write_run_scenario(o);
  const std::uint64_t run_id = o.run_id.value_or(fresh_run_id());
  const double discovery_timeout = discovery_timeout_s(o, plan.stations);
  const auto ready_timeout = std::chrono::milliseconds(std::llround(discovery_timeout * 1e3));

  // Discovery as for the flat exchange, whichever exchange the scans take: every station
  // hears every cluster's aggregator, and the lowest station's whole picture when peers part.
  ExchangeConfig everyone_meets = plan.scenario.exchange;
  everyone_meets.kind = ExchangeConfig::Kind::kFlat;
  const Placement placement(o, everyone_meets, ids.size());
  std::vector<int> node_ids = ids;  // the center (0) first, then the stations ascending
  node_ids.insert(node_ids.begin(), kCenterNodeId);
  // The live stream listens before the nodes start, so that a client can be there for the
  // first round.
  std::unique_ptr<PictureLiveFeed> live;
  if (o.live) {
    live = std::make_unique<PictureLiveFeed>(live_server_options(*o.live), o.live_scene_hz, plan,
                                             truth.targets);
    announce_live(*o.live, live->port());
  }
  RunNodes nodes(o, placement, ids, [&](const options::NetworkOptions& network) {
    options::NodeOptions child =
        node_options_for(o, network, scenario_file, run_id, discovery_timeout);
    if (recorded) child.traffic_file = std::filesystem::absolute(*recorded).string();
    child.overrides.stations = plan.stations;
    child.overrides.steps = plan.scenario.steps;
    child.overrides.mc_run = plan.mc_run;
    return options::to_arguments(child);
  });
  PictureDriver driver(harness_node_config(o, placement, plan.stations), run_id, node_ids,
                       [&] { nodes.check(); });
  try {
    nodes.start();
    const auto discovery_start = Clock::now();
    driver.wait_until_joined(ready_timeout);
    PictureRunSummary summary;
    summary.discovery_s = std::chrono::duration<double>(Clock::now() - discovery_start).count();
    // Endpoint discovery may go on after every node is ready (run/discovery_quiet.hpp).
    const QuietWait settled = nodes.wait_until_quiet();
    summary.settle_s = std::chrono::duration<double>(settled.waited).count();
    summary.settled_quiet = settled.quiet;
    const KernelSnapshot before_rounds = nodes.kernel_snapshot();

    summary.scenario = plan.scenario.name;
    summary.stations = plan.stations;
    summary.exchange = std::string(to_string(plan.scenario.exchange.kind));
    if (plan.scenario.exchange.kind == ExchangeConfig::Kind::kTree) {
      summary.fanout = plan.scenario.exchange.fanout;
    }
    summary.steps_planned = plan.scenario.steps;
    summary.stations_per_process = o.stations_per_process;
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
    ConnectionCheck connection(!realtime && !o.node.loss.enabled(), o.node.best_effort);
    int rounds_taken = 0;
    // `latency`: lock-step, from the tick to the last picture; real time, from the round's
    // scheduled end to its hand-over.
    const auto take_round = [&](int k, const std::vector<wire::PictureRound>& rounds,
                                std::chrono::duration<double, std::milli> latency) {
      connection.take(k, scans_missing(rounds, plan.stations));
      const PictureStep* scored = check.add(k, rounds);
      ++rounds_taken;
      if ((recording || live) && scored != nullptr) {
        PictureFrame frame = picture_frame(k, rounds, node_ids, *scored);
        frame.latency_ms = latency.count();
        if (live) live->offer(frame);
        if (recording) {
          add_scene(plan, truth.targets, frame);
          recording->add(frame);
        }
      }
      progress.advance();
    };
    // A run that stops once its rounds have begun keeps what it recorded, as one aircraft's
    // does: the nodes are stopped as after the last round, and every file is written before the
    // run is reported as stopped (StoppedEarlyWith).
    std::optional<RunAborted> stopped;
    try {
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
          apply_station_events(o, static_cast<std::uint64_t>(k), nodes, driver, ready_timeout);
          const auto tick = Clock::now();
          const auto rounds = driver.run_round(static_cast<std::uint32_t>(k), round_timeout);
          take_round(k, rounds, Clock::now() - tick);
        }
      }
    } catch (const RunAborted& e) {
      stopped = e;
    }
    const KernelSnapshot after_rounds = nodes.kernel_snapshot();
    summary.node_peak_resident_mib = nodes.peak_resident_mib();
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    progress.finish();
    summary.steps = rounds_taken;
    const double rounds = std::max(rounds_taken, 1);
    if (before_rounds.udp_datagrams && after_rounds.udp_datagrams) {
      summary.datagrams_per_round =
          static_cast<double>(*after_rounds.udp_datagrams - *before_rounds.udp_datagrams) / rounds;
    }
    summary.cpu_ms_per_station_round =
        1e3 * (after_rounds.cpu_s - before_rounds.cpu_s) / (plan.stations * rounds);
    summary.rounds_per_s = rounds_taken / seconds;
    summary.loss = o.node.loss.enabled();
    summary.faults = summary.loss || !o.kills.empty();
    summary.realtime = realtime;
    summary.gospa_mean = check.gospa_mean();
    summary.in_process_gospa_mean = twin.score.gospa_mean;
    if (stopped) {
      summary.stop_cause = stopped->cause();
      summary.end_detail = stopped->what();
    }
    // Nodes announce FINISHED after their last round and wait to be released; a run that
    // stopped early releases them at once.
    const auto finish_wait = stopped ? std::chrono::milliseconds(0) : std::chrono::seconds(5);
    for (const auto& [id, finished] : driver.wait_finished(finish_wait)) {
      if (id != kCenterNodeId) summary.resyncs += finished.resyncs;
      summary.lost += finished.lost;
      summary.dropped_by_node[id] = finished.dropped;
    }
    driver.release();
    nodes.finish(std::chrono::seconds(10), stopped.has_value());
    summary.node_exits = nodes.exits();

    write_file_atomically(out / "picture_rounds.csv", check.csv());
    const std::string summary_json = picture_run_json(summary, run_id, twin);
    write_file_atomically(out / "summary.json", summary_json + "\n");
    if (recording) recording->finish(summary_json, rounds_taken);
    if (live) finish_live(*live, summary_json);
    if (stopped) throw StoppedEarlyWith<PictureRunSummary>(*stopped, std::move(summary));
    return summary;
  } catch (...) {
    nodes.terminate();
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
