#include "run/picture_run.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "report/live_serving.hpp"
#include "report/output_files.hpp"
#include "report/picture_asterix.hpp"
#include "report/picture_live_source.hpp"
#include "report/picture_recording.hpp"
#include "report/picture_run_report.hpp"
#include "run/kernel_counters.hpp"
#include "run/lockstep_driver.hpp"
#include "run/picture_driver.hpp"
#include "run/picture_frame.hpp"
#include "run/picture_round_check.hpp"
#include "run/refusal_rows.hpp"
#include "run/run_over_dds.hpp"
#include "run/secure_start.hpp"
#include "skyfuse/asterix/udp.hpp"
#include "skyfuse/core/sorted_ids.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/sim/picture_run.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/scan_asterix.hpp"

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
        fmt::format("{}: not for a run of many aircraft yet: {} (docs/picture.md says what "
                    "runs over DDS so far)",
                    option, why));
  };
  if (!o.replay_path.empty()) {
    refuse("--replay",
           "a picture's stations replay an ASTERIX recording of their scans (--asterix-replay "
           "FILE.pcap) instead of measurements.csv");
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

// A unicast port is one socket's: of several stations listening on it, one alone would hear the
// feed. Several fed stations need a multicast group, each joining it.
void refuse_a_unicast_feed_for_several_stations(const RunOptions& o, const PicturePlan& plan) {
  if (o.node.asterix_in.empty()) return;
  std::string error;
  const auto listen = asterix::parse_udp_endpoint(o.node.asterix_in, error);
  if (!listen || asterix::is_multicast(*listen)) return;
  const auto participants = plan.participants();
  const auto fed =
      std::count_if(participants.begin(), participants.end(), [](const StationConfig& station) {
        return transport::carried_by_asterix(station.sensor.kind);
      });
  if (fed > 1) {
    throw std::invalid_argument(fmt::format(
        "--asterix-in: {} is a unicast address, and {} of the run's stations take a feed: a port "
        "of this host reaches one socket only; give a multicast group (224.0.0.0/4), which each "
        "station joins",
        o.node.asterix_in, fed));
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

// A run of many aircraft, as the house (run/run_over_dds.hpp) sees it: every node's picture of
// each round checked against the others' and the in-process twin's (PictureRoundCheck),
// recorded, streamed live, and written as picture_rounds.csv.
class ManyAircraftRun final : public RunKind {
 public:
  ManyAircraftRun(const RunOptions& o, const PicturePlan& plan)
      : o_(o), plan_(plan), ids_(sorted_ascending(plan.participant_ids())) {
    node_ids_ = ids_;  // the center (0) first, then the stations ascending
    node_ids_.insert(node_ids_.begin(), kCenterNodeId);
  }

  std::vector<int> station_ids() const override { return ids_; }
  int stations() const override { return plan_.stations; }
  int steps() const override { return plan_.scenario.steps; }
  std::string progress_label() const override {
    return fmt::format("picture M={}", plan_.stations);
  }
  // Discovery as for the flat exchange, whichever exchange the scans take: every station hears
  // every cluster's aggregator, and the lowest station's whole picture when peers part.
  ExchangeConfig placement_exchange() const override {
    ExchangeConfig everyone_meets = plan_.scenario.exchange;
    everyone_meets.kind = ExchangeConfig::Kind::kFlat;
    return everyone_meets;
  }
  // The nodes read the scenario's copy in the results folder: a recorded file it names
  // relative to itself is passed to them by its absolute path.
  void complete_node_options(options::NodeOptions& child) const override {
    if (const auto recorded = recorded_traffic_file(plan_.scenario, o_.node.traffic_file)) {
      child.traffic_file = std::filesystem::absolute(*recorded).string();
    }
    child.overrides.stations = plan_.stations;
    child.overrides.steps = plan_.scenario.steps;
    child.overrides.mc_run = plan_.mc_run;
  }

  // The in-process twin first: what every peer's picture must equal, round by round.
  void open(const transport::NodeConfig& config, std::uint64_t run_id,
            std::function<void()> check) override {
    truth_.emplace(build_traffic_truth(plan_.scenario, o_.node.traffic_file));
    // Fed a recording, the stations that replay it hold their simulated scans quantised as the
    // records hold them: so does the twin. A live feed is held to the same (it is one where a
    // recording of this scenario is sent; any other feed's picture is reported apart).
    ScanFilter quantised;
    if (!o_.node.asterix_replay.empty()) {
      summary_.asterix_feed = transport::count_asterix_feed(o_.node.asterix_replay);
    }
    if (!o_.node.asterix_replay.empty() || !o_.node.asterix_in.empty()) {
      quantised = [this](std::size_t s, Scan& scan) {
        const StationConfig& station = plan_.scenario.stations[s];
        if (auto q = transport::quantised_as_asterix({station.sensor.kind, scan, {}}, station,
                                                     plan_.scenario)) {
          scan = std::move(*q);
        }
      };
    }
    twin_.emplace(
        run_picture(plan_.scenario, truth_->targets, plan_.stations, plan_.mc_run, {}, quantised));
    if (o_.live) {
      live_ = std::make_unique<PictureLiveFeed>(live_server_options(*o_.live), o_.live_scene_hz,
                                                plan_, truth_->targets);
      announce_live(*o_.live, live_->port());
    }
    driver_.emplace(config, run_id, node_ids_, std::move(check));
  }
  NodeRoster& roster() override { return driver_->roster(); }

  void begin_rounds(std::uint64_t epoch_ns) override {
    check_.emplace(plan_, truth_->targets, *twin_, summary_);
    if (!o_.record_path.empty()) recording_.emplace(o_.record_path, plan_, epoch_ns);
    if (!o_.asterix_record_path.empty()) {
      asterix_.emplace(o_.asterix_record_path, plan_, node_ids_, truth_->targets);
    }
    if (live_) live_->set_epoch_ns(epoch_ns);
  }
  void run_lockstep_round(int k, std::chrono::milliseconds round_timeout,
                          ConnectionCheck& connection) override {
    const auto tick = Clock::now();
    const auto rounds = driver_->run_round(static_cast<std::uint32_t>(k), round_timeout);
    connection.take(k, scans_missing(rounds, plan_.stations));
    take(k, rounds, Clock::now() - tick);
  }
  void run_realtime(std::chrono::system_clock::time_point epoch, std::chrono::milliseconds,
                    const std::function<void()>& round_done) override {
    driver_->run_realtime(
        plan_.scenario.steps, plan_.scenario.time_step_s, epoch, kLateAfter,
        [&](int k, std::vector<wire::PictureRound> rounds) {
          const auto scheduled_end =
              epoch + std::chrono::duration_cast<std::chrono::system_clock::duration>(
                          std::chrono::duration<double>((k + 1) * plan_.scenario.time_step_s));
          take(k, rounds, std::chrono::system_clock::now() - scheduled_end);
          round_done();
        });
  }
  double rounds_worked() const override { return rounds_taken_; }
  void end(const ProcessMeasures& measured, std::uint64_t run_id) override;

  PictureRunSummary& summary() { return summary_; }

 private:
  // `latency`: lock-step, from the tick to the last picture; real time, from the round's
  // scheduled end to its hand-over.
  void take(int k, const std::vector<wire::PictureRound>& rounds,
            std::chrono::duration<double, std::milli> latency) {
    const PictureStep* scored = check_->add(k, rounds);
    ++rounds_taken_;
    if (asterix_) asterix_->add(k, rounds);
    // What the nodes reported refusing while the round was collected (the harness refuses
    // nothing of its own here: a picture of another run or step is passed over, not counted).
    append_refusal_rows(refusals_, static_cast<std::uint64_t>(k),
                        driver_->roster().take_refusals(static_cast<std::uint64_t>(k), {}));
    if ((recording_ || live_) && scored != nullptr) {
      PictureFrame frame = picture_frame(k, rounds, node_ids_, *scored);
      frame.latency_ms = latency.count();
      if (live_) live_->offer(frame);
      if (recording_) {
        add_scene(plan_, truth_->targets, frame);
        recording_->add(frame);
      }
    }
  }

  const RunOptions& o_;
  const PicturePlan& plan_;
  std::vector<int> ids_;
  std::vector<int> node_ids_;
  std::optional<TrafficTruth> truth_;
  std::optional<PictureRunResult> twin_;
  std::optional<PictureDriver> driver_;
  std::unique_ptr<PictureLiveFeed> live_;
  std::optional<PictureRoundCheck> check_;
  std::optional<PictureRecording> recording_;
  std::optional<PictureAsterixRecording> asterix_;
  int rounds_taken_ = 0;
  std::string refusals_{kRefusalsHeader};  // refusals.csv (run/refusal_rows.hpp)
  PictureRunSummary summary_;
};

void ManyAircraftRun::end(const ProcessMeasures& measured, std::uint64_t run_id) {
  PictureRunSummary& summary = summary_;
  summary.scenario = plan_.scenario.name;
  summary.stations = plan_.stations;
  summary.exchange = std::string(to_string(plan_.scenario.exchange.kind));
  if (plan_.scenario.exchange.kind == ExchangeConfig::Kind::kTree) {
    summary.fanout = plan_.scenario.exchange.fanout;
  }
  summary.steps_planned = plan_.scenario.steps;
  summary.stations_per_process = o_.stations_per_process;
  for (const auto& [id, finished] : driver_->roster().finished()) {
    if (id != kCenterNodeId) summary.resyncs += finished.resyncs;
    summary.lost += finished.lost;
    summary.dropped_by_node[id] = finished.dropped;
  }
  summary.take(measured);
  summary.steps = rounds_taken_;
  summary.rounds_per_s = rounds_taken_ / measured.rounds_s;
  summary.loss = o_.node.loss.enabled();
  summary.faults = summary.loss || !o_.kills.empty();
  summary.realtime = measured.realtime;
  const PictureSummary score = check_->score();
  summary.gospa_mean = score.gospa_mean;
  summary.gospa_in_view_mean = score.in_view.distance;
  summary.in_process_gospa_mean = twin_->score.gospa_mean;
  summary.in_process_gospa_in_view_mean = twin_->score.in_view.distance;
  const RealtimeLoad load{
      measured.realtime ? o_.node.realtime_deadline_ms : 0.0,
      static_cast<double>(summary.rounds_in_time) / std::max(summary.steps, 1), summary.steps,
      0.0};  // a picture's rounds never fall behind: a late one is handed over as it is
  summary.host_verdict = host_verdict(summary, load, plan_.scenario.time_step_s, cpu_model(),
                                      std::thread::hardware_concurrency());

  const std::filesystem::path out(o_.out_dir);
  write_file_atomically(out / "picture_rounds.csv", check_->csv());
  // The nodes' last statuses, as one aircraft's run lists them: reported in round `steps`.
  const auto steps = static_cast<std::uint64_t>(plan_.scenario.steps);
  append_refusal_rows(refusals_, steps, driver_->roster().take_refusals(steps, {}));
  write_file_atomically(out / "refusals.csv", refusals_);
  const std::string summary_json = picture_run_json(summary, run_id, *twin_);
  write_file_atomically(out / "summary.json", summary_json + "\n");
  if (recording_) recording_->finish(summary_json, rounds_taken_);
  if (asterix_) {
    asterix_->close();
    fmt::print(
        "ASTERIX CAT062 of every node's picture and CAT048/CAT021 of every station's scan in {} "
        "({} tracks and {} detections left out)\n",
        o_.asterix_record_path, asterix_->left_out(), asterix_->detections_left_out());
  }
  if (live_) finish_live(*live_, summary_json);
  if (measured.stopped) {
    throw StoppedEarlyWith<PictureRunSummary>(*measured.stopped, summary, summary.host_verdict);
  }
}

}  // namespace

PictureRunSummary execute_picture_run(const RunOptions& o, const PicturePlan& plan) {
  refuse_what_a_picture_run_lacks(o);
  refuse_a_unicast_feed_for_several_stations(o, plan);
  // A secure start on Fast DDS 2.9 sometimes stalls (secure_start.hpp).
  return with_secure_restarts(o, discovery_timeout_s(o, plan.stations),
                              [&](const RunOptions& attempt) {
                                ManyAircraftRun run(attempt, plan);
                                run_over_dds(attempt, run);
                                return std::move(run.summary());
                              });
}

}  // namespace skyfuse::harness
