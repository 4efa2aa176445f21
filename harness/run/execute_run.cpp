#include "run/execute_run.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <thread>

#include "report/live_serving.hpp"
#include "report/output_files.hpp"
#include "report/run_live_source.hpp"
#include "report/run_recording.hpp"
#include "run/kernel_counters.hpp"
#include "run/lockstep_driver.hpp"
#include "run/run_nodes.hpp"
#include "run/run_over_dds.hpp"
#include "run/secure_start.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/registry/filter_info.hpp"
#include "skyfuse/registry/part_info.hpp"
#include "skyfuse/transport/qos.hpp"

namespace skyfuse::harness {

void warn_if_receive_buffers_too_small(int stations) {
  if (const auto warning = transport::receive_buffer_warning(stations)) {
    fmt::print(stderr, "skyfuse: warning: {}\n", *warning);
  }
}

namespace {

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

// A run of one aircraft, as the house (run/run_over_dds.hpp) sees it: every node's track of
// each round recorded (RunRecorder), streamed live and written as its per-step CSVs.
class OneAircraftRun final : public RunKind {
 public:
  OneAircraftRun(const RunOptions& o, const RunPlan& plan)
      : o_(o), plan_(plan), ids_(plan.participant_ids()), recorder_(plan, ids_, o.restarts) {
    if (!o.asterix_record_path.empty()) {
      throw std::invalid_argument(
          "--asterix-record: for a run of many aircraft (a scenario with 'traffic'): one "
          "aircraft's run has no system tracks to number");
    }
  }

  std::vector<int> station_ids() const override { return ids_; }
  int stations() const override { return plan_.stations; }
  int steps() const override { return plan_.scenario.steps; }
  std::string progress_label() const override {
    return fmt::format("run M={} {:.0f} km/h", plan_.stations, plan_.speed_mps * 3.6);
  }
  ExchangeConfig placement_exchange() const override { return plan_.scenario.exchange; }
  // Every node builds the same plan as the harness.
  void complete_node_options(options::NodeOptions& child) const override {
    child.overrides = {plan_.stations, plan_.scenario.steps,         plan_.speed_mps * 3.6,
                       plan_.mc_run,   plan_.scenario.exchange.kind, plan_.scenario.exchange.fanout,
                       std::nullopt,   // one target: no aircraft to count
                       std::nullopt};  // nor anything to associate
  }
  std::vector<std::string> station_arguments() const override {
    if (o_.replay_path.empty()) return {};
    return {"--replay", std::filesystem::absolute(o_.replay_path).string()};
  }

  void open(const transport::NodeConfig& config, std::uint64_t run_id,
            std::function<void()> check) override {
    const TrackShape shape{find_motion_model(plan_.scenario.filter.motion_model.kind)->state_dim,
                           find_filter(plan_.scenario.filter)->mode_names.size()};
    driver_.emplace(config, run_id, plan_.participants(), shape, std::move(check));
    if (o_.live) {
      live_ =
          std::make_unique<LiveFeed>(live_server_options(*o_.live), o_.live_scene_hz, recorder_);
      announce_live(*o_.live, live_->port());
    }
  }
  NodeRoster& roster() override { return driver_->roster(); }

  void begin_rounds(std::uint64_t epoch_ns) override {
    epoch_ns_ = epoch_ns;
    if (live_) live_->set_epoch_ns(epoch_ns);
  }
  // A round closes at a deadline like the nodes' own, so that a node that is down or late is
  // recorded as missing instead of stalling the run.
  void run_lockstep_round(int k, std::chrono::milliseconds round_timeout,
                          ConnectionCheck& connection) override {
    const auto close_after =
        std::chrono::milliseconds(std::llround(2.0 * o_.node.round_deadline_ms + 250.0));
    RoundRecord round =
        driver_->run_round(static_cast<std::uint64_t>(k), close_after, round_timeout);
    connection.take(k, missing_from(round, ids_.size()));
    take(std::move(round));
  }
  void run_realtime(std::chrono::system_clock::time_point epoch,
                    std::chrono::milliseconds round_timeout,
                    const std::function<void()>& round_done) override {
    driver_->run_realtime(plan_.scenario.steps, plan_.scenario.time_step_s, epoch, round_timeout,
                          [&](RoundRecord r) {
                            take(std::move(r));
                            round_done();
                          });
  }
  // In real time, as far as any node got.
  double rounds_worked() const override {
    double rounds = static_cast<double>(recorder_.rounds().size());
    if (o_.node.realtime_deadline_ms > 0.0) {
      rounds = std::max(rounds, static_cast<double>(driver_->realtime_progress().steps_reached));
    }
    return rounds;
  }
  void end(const ProcessMeasures& measured, std::uint64_t run_id) override;

  RunSummary& summary() { return summary_; }

 private:
  void take(RoundRecord round) {
    if (live_) live_->offer(round);
    recorder_.add(std::move(round));
  }

  const RunOptions& o_;
  const RunPlan& plan_;
  std::vector<int> ids_;
  RunRecorder recorder_;
  std::optional<LockstepDriver> driver_;
  std::unique_ptr<LiveFeed> live_;
  std::uint64_t epoch_ns_ = 0;
  RunSummary summary_;
};

void OneAircraftRun::end(const ProcessMeasures& measured, std::uint64_t run_id) {
  RunSummary& summary = summary_;
  summary = recorder_.summarise(measured.discovery_s, measured.rounds_s);
  summary.take(measured);
  summary.realtime_deadline_ms = o_.node.realtime_deadline_ms;
  if (measured.realtime) {
    const LockstepDriver::RealtimeProgress reached = driver_->realtime_progress();
    summary.realtime_steps_scheduled = reached.steps_scheduled;
    summary.realtime_steps_reached = reached.steps_reached;
    if (measured.stopped) summary.realtime_behind_s = reached.behind_s;
  }
  summary.node_counts = driver_->finished_counts();
  recorder_.set_refusals_after_run(
      driver_->take_refusals(static_cast<std::uint64_t>(plan_.scenario.steps)));
  summary.round_deadline_ms = o_.node.round_deadline_ms;
  summary.loss = o_.node.loss;
  summary.best_effort = o_.node.best_effort;
  summary.hosts = o_.hosts;
  summary.stations_per_process = o_.stations_per_process;
  summary.refusion_lag = o_.node.refusion_lag;
  recorder_.set_settled(driver_->settled_tracks());
  summary.settled = recorder_.summarise_settled();
  const RealtimeLoad load{o_.node.realtime_deadline_ms, summary.rounds_all_inputs_in_time,
                          summary.steps - summary.rounds_closed_incomplete,
                          summary.realtime_behind_s};
  summary.host_verdict = host_verdict(summary, load, plan_.scenario.time_step_s, cpu_model(),
                                      std::thread::hardware_concurrency());
  const std::filesystem::path out(o_.out_dir);
  recorder_.write(out, summary, run_id);
  const std::string summary_json = recorder_.summary_json(summary, run_id);
  if (live_) finish_live(*live_, summary_json);
  if (!o_.record_path.empty()) {
    write_recording(recorder_, summary_json, o_.record_path, epoch_ns_);
  }
  if (measured.stopped) {
    std::string verdict = summary.host_verdict;
    throw StoppedEarlyWith<RunSummary>(*measured.stopped, summary, std::move(verdict));
  }
}

}  // namespace

RunSummary execute_run(const RunOptions& o, const RunPlan& plan) {
  // A secure start on Fast DDS 2.9 sometimes stalls (secure_start.hpp).
  return with_secure_restarts(o, discovery_timeout_s(o, plan.stations),
                              [&](const RunOptions& attempt) {
                                OneAircraftRun run(attempt, plan);
                                run_over_dds(attempt, run);
                                return std::move(run.summary());
                              });
}

}  // namespace skyfuse::harness
