#include "center_process.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <variant>
#include <vector>

#include "central_fusion.hpp"
#include "skyfuse/registry/dispatch.hpp"
#include "skyfuse/tracking/round_rule.hpp"
#include "skyfuse/tracking/step_collector.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/delayed_inbox.hpp"
#include "skyfuse/transport/drop_log.hpp"
#include "skyfuse/transport/node_presence.hpp"
#include "skyfuse/transport/node_setup.hpp"
#include "skyfuse/transport/realtime_schedule.hpp"
#include "skyfuse/transport/shutdown.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "skyfuse/transport/wire_conversion.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse::center {
namespace {

using namespace std::chrono_literals;

constexpr auto kPollSlice = 50ms;

// What a fusion that takes a fixed-lag re-fusion keeps of each round in the lag: its state. One
// that takes none keeps nothing.
template <typename Fusion>
struct PriorOf {
  using type = std::monostate;
};
template <typename Fusion>
requires Fusion::kRefuses struct PriorOf<Fusion> {
  using type = typename Fusion::State;
};

// The center for stations of `Sensor` (one sensor type, or a SensorPack when they differ),
// whose rounds `Fusion` updates: what the run's filter part runs at the center
// (central_fusion.hpp, CenterFusionOf).
template <typename Sensor, typename Fusion>
class Center {
 public:
  using Observation = ObservationFor<Sensor>;

  Center(const options::NodeOptions& options, const RunPlan& plan)
      : options_(options),
        plan_(plan),
        node_(transport::node_config(options, "skyfuse-center")),
        presence_(node_, options.run_id, kCenterSourceId),
        ticks_(node_.make_reader<wire::Tick>()),
        measurements_(node_.make_reader<wire::Measurement>()),
        tracks_(node_.make_writer<wire::TrackEstimate>()),
        fusion_(plan),
        collector_(plan.participant_ids(), options.refusion_lag) {
    // (load_plan refuses a lag for a fusion that takes none.)
    if constexpr (Fusion::kRefuses) priors_.assign(options.refusion_lag + 1, fusion_.state());
    final_tracks_.resize(options.refusion_lag + 1);
    wait_set_.attach(ticks_);
    wait_set_.attach(measurements_);
  }

  int run() {
    const int m = plan_.stations;
    const transport::JoinResult joined = transport::join_run(
        presence_,
        [&] {
          return measurements_.matched() >= m && ticks_.matched() >= 1 && tracks_.matched() >= 1;
        },
        [&] {
          return fmt::format("measurement writers {}/{}, tick writer {}/1, track readers {}/1",
                             measurements_.matched(), m, ticks_.matched(), tracks_.matched());
        },
        options_.discovery_timeout());
    if (const auto code = transport::exit_code_unless_joined(
            joined, presence_, "a fusion center", options_.run_id, options_.discovery_timeout_s)) {
      return *code;
    }
    spdlog::info("joined run {} with {} stations", options_.run_id, m);

    const auto steps = static_cast<std::uint64_t>(plan_.scenario.steps);
    for (std::uint64_t k = 0; k < steps; ++k) {
      if (const int code = wait_for_measurements(k); code >= 0) return code;
      // The measurements that arrived by the deadline, screened and stacked by the round rule,
      // as the in-process twin does: both compute the same bits.
      const NumericalStatus status = update_round(k);
      if (status != NumericalStatus::kOk) {
        const std::string detail =
            fmt::format("step {}: stacked update failed: {}", k, to_string(status));
        spdlog::error("{}", detail);
        presence_.set_drops(drops_.counts());  // a failure report says what was refused too
        presence_.announce(wire::FAILED, static_cast<std::uint32_t>(k), detail);
        return options::kExitNumerical;
      }
      tracks_.write(final_tracks_[k % final_tracks_.size()]);  // built by update_rounds
      if constexpr (Fusion::kRefuses) {
        const std::uint64_t lag = collector_.lag();
        if (lag != 0 && k >= lag) tracks_.write(settled_track(k - lag));  // leaves the lag
      }
      fusion_.predict();
      if constexpr (Fusion::kRefuses) {
        if (collector_.lag() != 0) prior_of(k + 1) = fusion_.state();  // the lag's history
      }
      collector_.advance();
    }
    if constexpr (Fusion::kRefuses) {
      if (const int code = settle_the_lag(steps); code >= 0) return code;
    }
    presence_.set_drops(drops_.counts());
    presence_.set_link_counts(lost_, 0, late_used_);
    presence_.announce(wire::FINISHED, static_cast<std::uint32_t>(steps));
    transport::finish_when_released(ticks_, options_.run_id, presence_, tracks_, 5s);
    spdlog::info("finished {} steps", steps);
    return options::kExitOk;
  }

 private:
  // Updates round k with the measurements that arrived by the round rule, as the in-process
  // twin does, so both compute the same bits. With a re-fusion lag, the rounds that late
  // measurements came for are updated again first, from the earliest one's prior (the
  // out-of-sequence measurements enter the track where they belong).
  NumericalStatus update_round(std::uint64_t k) {
    std::uint64_t from = k;
    if constexpr (Fusion::kRefuses) {
      if (late_from_ && *late_from_ < k) {
        from = *late_from_;
        fusion_.reset_to(prior_of(from));
      }
      late_from_.reset();
    }
    return update_rounds(from, k, k);
  }

  // Updates rounds [from, to], the fusion holding round `from`'s prior; the refusals of round
  // `closing` (the one closing now, if any) are counted.
  NumericalStatus update_rounds(std::uint64_t from, std::uint64_t to,
                                std::optional<std::uint64_t> closing) {
    for (std::uint64_t q = from; q <= to; ++q) {
      if (q > from) {
        fusion_.predict();
        if constexpr (Fusion::kRefuses) prior_of(q) = fusion_.state();
      }
      const NumericalStatus status = fusion_.update(
          collector_.station_ids().size(),
          [&](std::size_t j) {
            return collector_.filled_at(q, j) ? &collector_.payload_at(q, j) : nullptr;
          },
          options_.nis_gate(),
          [&](int station_id, DropKind why) {  // counted once: when the round closes
            if (q == closing) transport::count_drop(drops_, why, "measurement", station_id, q);
          });
      if (status != NumericalStatus::kOk) return status;
      final_tracks_[q % final_tracks_.size()] = fusion_.track(options_.run_id, q, kCenterSourceId);
    }
    return NumericalStatus::kOk;
  }

  auto& prior_of(std::uint64_t step) { return priors_[step % priors_.size()]; }

  // Round `step`'s final estimate, as it leaves the lag.
  wire::TrackEstimate settled_track(std::uint64_t step) const {
    wire::TrackEstimate track = final_tracks_[step % final_tracks_.size()];
    track.settled(true);
    return track;
  }

  // After the last round, with a re-fusion lag: in real time, waits a lag's worth of steps for
  // late measurements; then updates the rounds they came for again and sends the final tracks
  // of the rounds still in the lag. Returns an exit code if the run must end, -1 otherwise.
  int settle_the_lag(std::uint64_t steps) {
    const std::uint64_t lag = collector_.lag();
    if (lag == 0 || steps == 0) return -1;
    if (options_.realtime_deadline_ms > 0.0) {
      const auto until = std::chrono::steady_clock::now() +
                         transport::steps_duration(lag, plan_.scenario.time_step_s);
      while (std::chrono::steady_clock::now() < until) {
        if (transport::shutdown_requested()) return 128 + transport::shutdown_signal();
        drain_measurements();
        wait_set_.wait(delayed_.wait_limit(
            std::chrono::steady_clock::now(),
            std::clamp(std::chrono::duration_cast<std::chrono::microseconds>(
                           until - std::chrono::steady_clock::now()),
                       std::chrono::microseconds(1),
                       std::chrono::duration_cast<std::chrono::microseconds>(kPollSlice))));
      }
    }
    if (late_from_) {
      fusion_.reset_to(prior_of(*late_from_));
      const NumericalStatus status = update_rounds(*late_from_, steps - 1, std::nullopt);
      late_from_.reset();
      if (status != NumericalStatus::kOk) {
        const std::string detail =
            fmt::format("settling the last rounds: stacked update failed: {}", to_string(status));
        spdlog::error("{}", detail);
        presence_.announce(wire::FAILED, static_cast<std::uint32_t>(steps), detail);
        return options::kExitNumerical;
      }
    }
    for (std::uint64_t s = steps > lag ? steps - lag : 0; s < steps; ++s) {
      tracks_.write(settled_track(s));
    }
    tracks_.wait_acknowledged(2s);  // before FINISHED: the harness stops reading then
    return -1;
  }

  // Waits until every measurement of step k is in, or the round's deadline passes: in lock-step
  // the deadline runs from tick k, in real time from the step's scheduled start (after the
  // start tick). Measurements that arrive before the tick are kept all the same.
  int wait_for_measurements(std::uint64_t k) {
    const bool realtime = options_.realtime_deadline_ms > 0.0;
    const auto limit = k == 0 ? options_.first_tick_timeout() : options_.idle_timeout();
    const auto idle_limit = std::chrono::steady_clock::now() + limit;
    std::optional<std::chrono::system_clock::time_point> close;
    while (true) {
      if (const auto code =
              transport::exit_code_if_duplicate(presence_, "a fusion center", options_.run_id)) {
        return *code;
      }
      wire::Tick tick;
      while (ticks_.take(tick)) {
        if (tick.run_id() != options_.run_id) {
          transport::count_drop(drops_, DropKind::kWrongRun, "tick", 0, tick.step());
          continue;
        }
        if (tick.epoch_ns() != 0) epoch_ns_ = tick.epoch_ns();
        if (tick.stop()) {
          spdlog::info("stopped by the harness at step {}", k);
          return options::kExitOk;
        }
        if (!realtime && tick.step() == k && !close) {
          close = std::chrono::system_clock::now() + options_.round_deadline();
        }
      }
      drain_measurements();
      if (collector_.complete()) return -1;
      if (realtime && epoch_ns_ != 0) {
        close = transport::step_start(epoch_ns_, k, plan_.scenario.time_step_s) +
                options_.realtime_deadline();
      }
      if (close && std::chrono::system_clock::now() >= *close) return -1;
      if (transport::shutdown_requested()) return 128 + transport::shutdown_signal();
      if (std::chrono::steady_clock::now() >= idle_limit) {
        const std::string detail =
            fmt::format("no progress for {} s at step {} waiting for measurements of stations {}",
                        std::chrono::duration<double>(limit).count(), k, collector_.missing());
        spdlog::error("{}", detail);
        presence_.set_drops(drops_.counts());  // a failure report says what was refused too
        presence_.announce(wire::FAILED, static_cast<std::uint32_t>(k), detail);
        return options::kExitIdleTimeout;
      }
      auto slice = std::chrono::duration_cast<std::chrono::microseconds>(kPollSlice);
      if (close) {  // never sleep past the deadline
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(
            *close - std::chrono::system_clock::now());
        slice =
            std::clamp(left + std::chrono::microseconds(1), std::chrono::microseconds(1), slice);
      }
      // Nor past the next delayed measurement.
      wait_set_.wait(delayed_.wait_limit(std::chrono::steady_clock::now(), slice));
    }
  }

  // Takes what the measurement reader holds through the simulated link (loss, delay) and
  // receives what is due.
  void drain_measurements() {
    wire::Measurement sample;
    transport::WriterId writer;
    const auto now = std::chrono::steady_clock::now();
    while (measurements_.take(sample, &writer)) {
      if (options_.loss.lost(kCenterSourceId, sample.station_id(), sample.step())) {
        ++lost_;  // the simulated link lost it: as if it never arrived
        continue;
      }
      if (options_.delay.enabled()) {  // the simulated link holds it back
        delayed_.hold(
            sample, writer,
            now + options_.delay.of(options_.loss.seed, kCenterSourceId,
                                    static_cast<int>(sample.station_id()), sample.step()));
        continue;
      }
      receive(sample, writer);
    }
    delayed_.release_due(
        now, [&](const wire::Measurement& m, const transport::WriterId& w) { receive(m, w); });
  }

  // Checks a received measurement and keeps it, or counts why not.
  void receive(const wire::Measurement& sample, const transport::WriterId& writer) {
    if (const auto why = refusal(sample, writer)) {
      transport::count_drop(drops_, *why, "measurement", sample.station_id(), sample.step());
    }
  }

  // Checks a received measurement and offers it to the collector; nothing if it was kept.
  std::optional<DropKind> refusal(const wire::Measurement& sample,
                                  const transport::WriterId& writer) {
    if (sample.run_id() != options_.run_id) return DropKind::kWrongRun;
    // Garbage is garbage whoever sent it; then who it claims to be and when; then whether the
    // writer really speaks for that station.
    const auto received = transport::observation_for<Sensor>(sample);
    if (!received) return DropKind::kOutOfRange;  // another sensor kind, or other lengths
    const Observation& observation = *received;
    // An unknown id is left to admit(), which says so.
    const StationConfig* station = plan_.participant(sample.station_id());
    if (const auto why = with_observation(
            observation, [&](const auto& o) { return check_station_measurement(o, station); })) {
      return why;
    }
    const auto why = transport::admit(collector_, sources_, sample.step(), sample.station_id(),
                                      writer, observation);
    if (!why && sample.step() < collector_.current_step()) {  // late, within the lag
      ++late_used_;
      late_from_ = std::min<std::uint64_t>(late_from_.value_or(sample.step()), sample.step());
    }
    return why;
  }

  const options::NodeOptions& options_;
  const RunPlan& plan_;
  transport::DdsNode node_;
  transport::NodePresence presence_;
  transport::Reader<wire::Tick> ticks_;
  transport::Reader<wire::Measurement> measurements_;
  transport::Writer<wire::TrackEstimate> tracks_;
  transport::ReaderWaitSet wait_set_;
  Fusion fusion_;
  StepCollector<Observation> collector_;
  std::uint64_t epoch_ns_ = 0;  // real time: system-clock start of step 0
  transport::SourceBinding sources_;
  DropTally drops_;
  std::uint64_t lost_ = 0;  // measurements removed by the simulated loss
  transport::DelayedInbox<wire::Measurement> delayed_;  // held by --link-delay-ms
  // Fixed-lag re-fusion: each round's prior in the lag, the oldest round a late measurement
  // came for since the last update, and how many came.
  std::vector<typename PriorOf<Fusion>::type> priors_;
  // Each round's latest track while it is in the lag (without one: the round just updated).
  std::vector<wire::TrackEstimate> final_tracks_;
  std::optional<std::uint64_t> late_from_;
  std::uint64_t late_used_ = 0;
};

}  // namespace

int run_center(const options::NodeOptions& options) {
  const RunPlan plan = transport::load_plan(options);
  int code = options::kExitError;
  dispatch_configuration(
      plan.scenario, plan.stations,
      [&]<typename Model, template <int> class SensorOf>(std::type_identity<Model>,
                                                         SensorTemplate<SensorOf>) {
        using Sensor = SensorOf<Model::kDim>;
        visit_filter_kind<FilterParts>(
            plan.scenario.filter.kind, [&]<typename Filter>(std::type_identity<Filter>) {
              // The loader gives a filter only the models and stations it runs on.
              if constexpr (filter_runs_on<Filter, Model, Sensor>()) {
                Center<Sensor, typename CenterFusionOf<Filter, Model, Sensor>::type> center(options,
                                                                                            plan);
                code = center.run();
              } else {
                throw std::logic_error(fmt::format("filter {} on {} with these stations",
                                                   Filter::kKind, Model::kKind));
              }
            });
      });
  return code;
}

}  // namespace skyfuse::center
