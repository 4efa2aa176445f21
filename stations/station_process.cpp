#include "station_process.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include "skyfuse/registry/registry.hpp"
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
#include "station_fusions.hpp"

namespace skyfuse::station {
namespace {

using namespace std::chrono_literals;
using options::ExitCode;

constexpr auto kPollSlice = 50ms;

// The DDS side of a station: its endpoints, created in a fixed order.
struct StationEndpoints {
  explicit StationEndpoints(transport::DdsNode& node)
      : ticks(node.make_reader<wire::Tick>()),
        increments_in(node.make_reader<wire::InformationIncrement>()),
        increments_out(node.make_writer<wire::InformationIncrement>()),
        measurements(node.make_writer<wire::Measurement>()),
        tracks(node.make_writer<wire::TrackEstimate>()) {
    wait_set.attach(ticks);
    wait_set.attach(increments_in);
  }
  transport::Reader<wire::Tick> ticks;
  transport::Reader<wire::InformationIncrement> increments_in;
  transport::Writer<wire::InformationIncrement> increments_out;
  transport::Writer<wire::Measurement> measurements;
  transport::Writer<wire::TrackEstimate> tracks;
  transport::ReaderWaitSet wait_set;
};

// A station with a `Sensor` of the run's motion model's state (a radar, the aircraft's GPS, a
// TDOA receiver), whose rounds `Fusion` fuses: the fusion of the run's filter part
// (station_fusions.hpp).
template <typename Sensor, typename Fusion>
class Station {
 public:
  Station(const StationOptions& options, const RunPlan& plan, const StationConfig& me,
          std::unique_ptr<SensorSource<Sensor>> source)
      : options_(options),
        plan_(plan),
        me_(me),
        source_(std::move(source)),
        node_(transport::node_config(options.node, fmt::format("skyfuse-station-{}", me.id))),
        presence_(node_, options.node.run_id, me.id),
        io_(node_),
        fusion_(plan, options.node.refusion_lag),
        sensor_(make_sensor<Sensor>(me)),
        noise_(station_noise_covariance<Sensor::kMeasDim>(plan.scenario, me, plan.mc_run)),
        syncing_(options.rejoin_step.has_value()) {
    sources_.bind(me_.id, io_.increments_out.id());
  }

  int run() {
    const int m = plan_.stations;
    // Matched counts include this participant's own endpoints: M increment writers (every
    // station, this one too); the measurement goes to the center and the harness's recorder.
    const transport::JoinResult joined = transport::join_run(
        presence_,
        [&] {
          return io_.increments_in.matched() >= m && io_.increments_out.matched() >= m &&
                 io_.ticks.matched() >= 1 && io_.measurements.matched() >= 2 &&
                 io_.tracks.matched() >= 1;
        },
        [&] {
          return fmt::format(
              "increment writers {}/{}, increment readers {}/{}, tick writer {}/1, measurement "
              "readers {}/2 (center, harness), track readers {}/1 (harness)",
              io_.increments_in.matched(), m, io_.increments_out.matched(), m, io_.ticks.matched(),
              io_.measurements.matched(), io_.tracks.matched());
        },
        options_.node.discovery_timeout());
    if (const auto code = transport::exit_code_unless_joined(
            joined, presence_, fmt::format("station {}", me_.id), options_.node.run_id,
            options_.node.discovery_timeout_s)) {
      return *code;
    }
    spdlog::info("joined run {} with {} stations; waiting for ticks", options_.node.run_id, m);

    const auto steps = static_cast<std::uint64_t>(plan_.scenario.steps);
    const std::uint64_t first = options_.rejoin_step.value_or(0);
    fusion_.start_at(first);
    const bool realtime = options_.node.realtime_deadline_ms > 0.0;
    if (realtime) {
      bool started = false;
      if (const int code = wait(
              0, started, options_.node.first_tick_timeout(), [&] { return epoch_ns_ != 0; },
              [] { return std::string("the start tick"); });
          code >= 0) {
        return code;
      }
    }
    for (std::uint64_t k = first; k < steps; ++k) {
      // Real time: step k starts on the wall clock. Lock-step: on its tick. Either way the
      // round closes when every increment is in or at its deadline, with what has arrived.
      std::chrono::system_clock::time_point close;
      if (realtime) {
        const auto start = step_start(k);
        std::this_thread::sleep_until(start);
        close = start + options_.node.realtime_deadline();
      } else {
        const auto limit =
            k == first ? options_.node.first_tick_timeout() : options_.node.idle_timeout();
        if (const int code = wait_for_tick(k, limit); code >= 0) return code;
        close = std::chrono::system_clock::now() + options_.node.round_deadline();
      }
      publish_own_sample(k);
      if (const int code = wait_until_closed(k, close); code >= 0) return code;
      if (const int code = fuse_and_publish(k); code >= 0) return code;
      fusion_.advance();
    }
    if (const int code = settle_the_lag(steps); code >= 0) return code;
    presence_.set_drops(drops_.counts());
    presence_.set_link_counts(lost_, resyncs_, fusion_.late_used());
    presence_.announce(wire::FINISHED, static_cast<std::uint32_t>(steps));
    transport::finish_when_released(io_.ticks, options_.node.run_id, presence_, io_.tracks, 5s);
    spdlog::info(
        "finished {} steps ({} rounds resynchronised, {} samples lost to --loss, {} late ones "
        "re-fused)",
        steps - first, resyncs_, lost_, fusion_.late_used());
    return options::kExitOk;
  }

 private:
  // Drains both readers. Returns an exit code if the run must end, -1 otherwise.
  int drain(std::uint64_t k, bool& got_tick) {
    if (const auto code = transport::exit_code_if_duplicate(
            presence_, fmt::format("station {}", me_.id), options_.node.run_id)) {
      return *code;
    }
    wire::Tick tick;
    while (io_.ticks.take(tick)) {
      if (tick.run_id() != options_.node.run_id) {
        transport::count_drop(drops_, DropKind::kWrongRun, "tick", 0, tick.step());
        continue;
      }
      if (tick.stop()) {
        spdlog::info("stopped by the harness at step {}", k);
        return options::kExitOk;
      }
      if (tick.epoch_ns() != 0) epoch_ns_ = tick.epoch_ns();
      if (tick.step() == k) got_tick = true;
    }
    wire::InformationIncrement sample;
    transport::WriterId writer;
    const auto now = std::chrono::steady_clock::now();
    while (io_.increments_in.take(sample, &writer)) {
      if (sample.station_id() == me_.id && writer == io_.increments_out.id()) continue;  // own
      if (options_.node.loss.lost(me_.id, sample.station_id(), sample.step())) {
        ++lost_;  // the simulated link lost it: as if it never arrived
        continue;
      }
      if (options_.node.delay.enabled()) {  // the simulated link holds it back
        delayed_.hold(
            sample, writer,
            now + options_.node.delay.of(options_.node.loss.seed, me_.id,
                                         static_cast<int>(sample.station_id()), sample.step()));
        continue;
      }
      receive(sample, writer);
    }
    delayed_.release_due(now, [&](const wire::InformationIncrement& s,
                                  const transport::WriterId& w) { receive(s, w); });
    return -1;
  }

  // Checks a received increment and keeps it, or counts why not.
  void receive(const wire::InformationIncrement& sample, const transport::WriterId& writer) {
    if (const auto why = refusal(sample, writer)) {
      transport::count_drop(drops_, *why, "increment", sample.station_id(), sample.step());
    }
  }

  // How long to wait for samples: a poll slice at most, and not past the next delayed one.
  std::chrono::microseconds wait_slice(std::chrono::microseconds longest = kPollSlice) const {
    return delayed_.wait_limit(std::chrono::steady_clock::now(), longest);
  }

  // Checks a received increment and offers it to the collector; nothing if it was kept.
  std::optional<DropKind> refusal(const wire::InformationIncrement& sample,
                                  const transport::WriterId& writer) {
    if (sample.run_id() != options_.node.run_id) return DropKind::kWrongRun;
    // Garbage is garbage whoever sent it; then who it claims to be and when; then whether the
    // writer really speaks for that station.
    return fusion_.admit(sample, writer, sources_);
  }

  // Waits until `done()` or for `limit` at most; returns an exit code to end the run, or -1.
  template <typename Done, typename Describe>
  int wait(std::uint64_t k, bool& got_tick, std::chrono::milliseconds limit, Done done,
           Describe what) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (true) {
      if (const int code = drain(k, got_tick); code >= 0) return code;
      if (done()) return -1;
      if (transport::shutdown_requested()) return 128 + transport::shutdown_signal();
      if (std::chrono::steady_clock::now() >= deadline) {
        const std::string detail =
            fmt::format("no progress for {} s at step {} waiting for {}",
                        std::chrono::duration<double>(limit).count(), k, what());
        spdlog::error("{}", detail);
        presence_.set_drops(drops_.counts());  // a failure report says what was refused too
        presence_.announce(wire::FAILED, static_cast<std::uint32_t>(k), detail);
        return options::kExitIdleTimeout;
      }
      io_.wait_set.wait(wait_slice());
    }
  }

  int wait_for_tick(std::uint64_t k, std::chrono::milliseconds limit) {
    bool got_tick = false;
    return wait(
        k, got_tick, limit, [&] { return got_tick; }, [] { return std::string("the tick"); });
  }

  std::chrono::system_clock::time_point step_start(std::uint64_t k) const {
    return transport::step_start(epoch_ns_, k, plan_.scenario.time_step_s);
  }

  // Collects increments until every expected one is in (all but this station's own while it
  // resynchronises) or `close` passes; either is fine.
  int wait_until_closed(std::uint64_t k, std::chrono::system_clock::time_point close) {
    const std::size_t expected = fusion_.station_ids().size() - (syncing_ ? 1 : 0);
    bool unused = false;
    while (true) {
      if (const int code = drain(k, unused); code >= 0) return code;
      if (fusion_.arrived_count() == expected) return -1;
      if (transport::shutdown_requested()) return 128 + transport::shutdown_signal();
      const auto left = close - std::chrono::system_clock::now();
      if (left <= std::chrono::system_clock::duration::zero()) return -1;
      io_.wait_set.wait(wait_slice(std::min<std::chrono::microseconds>(
          std::chrono::duration_cast<std::chrono::microseconds>(left) + 1us, kPollSlice)));
    }
  }

  void publish_own_sample(std::uint64_t k) {
    const auto step = static_cast<std::uint32_t>(k);
    const StationObservation<Sensor> observation{me_.id, sensor_, source_->measurement(k), noise_};
    io_.measurements.write(transport::to_wire(observation, options_.node.run_id, step));
    if (syncing_) return;  // no prior yet: nothing to compute an increment against

    // The round rule screens it as the center does, so both architectures fuse the same
    // measurements; screened out, it still yields a zero increment that tells the peers not to
    // wait for one.
    const OwnContribution result = fusion_.contribute(
        k, observation, options_.node.nis_gate(), options_.node.run_id,
        [&](const wire::InformationIncrement& s) { io_.increments_out.write(s); });
    if (result.refused) {
      transport::count_drop(drops_, *result.refused, "own measurement", me_.id, k);
    } else if (result.status != NumericalStatus::kOk) {
      throw std::runtime_error(
          fmt::format("step {}: increment failed: {}", k, to_string(result.status)));
    }
  }

  int fuse_and_publish(std::uint64_t k) {
    // What arrived (everything, in a healthy lock-step round), by the round rule; the track
    // names exactly these stations.
    const RoundFusion fused = fusion_.fuse([&](int station_id, DropKind why) {
      transport::count_drop(drops_, why, "increment", station_id, k);
    });
    if (!fusion_.arrived()) {  // only while resynchronising: no peer's prior arrived this round
      spdlog::warn("step {}: no peer increment arrived; still without a prior", k);
      return -1;
    }
    if (fused.status != NumericalStatus::kOk) {
      const std::string detail =
          fmt::format("step {}: fusion failed: {}", k, to_string(fused.status));
      spdlog::error("{}", detail);
      presence_.set_drops(drops_.counts());  // a failure report says what was refused too
      presence_.announce(wire::FAILED, static_cast<std::uint32_t>(k), detail);
      return options::kExitNumerical;
    }
    if (fused.resynced) {
      ++resyncs_;
      if (syncing_)
        spdlog::info("step {}: took the peers' prior; contributing from step {}", k, k + 1);
    }
    syncing_ = false;
    io_.tracks.write(fusion_.track(options_.node.run_id, k, me_.id));
    if (const auto settled = fusion_.settled_round()) {  // leaves the lag: final now
      io_.tracks.write(fusion_.settled_track(options_.node.run_id, *settled, me_.id));
    }
    fusion_.predict();
    return -1;
  }

  // After the last round, with a re-fusion lag: in real time, waits a lag's worth of steps for
  // late increments; then fuses the rounds still in the lag again and sends their final tracks.
  // Returns an exit code if the run must end, -1 otherwise.
  int settle_the_lag(std::uint64_t steps) {
    if (options_.node.refusion_lag == 0) return -1;
    if (options_.node.realtime_deadline_ms > 0.0) {
      const auto until =
          std::chrono::steady_clock::now() +
          transport::steps_duration(options_.node.refusion_lag, plan_.scenario.time_step_s);
      bool unused = false;
      while (std::chrono::steady_clock::now() < until) {
        if (const int code = drain(steps, unused); code >= 0) return code;
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(
            until - std::chrono::steady_clock::now());
        io_.wait_set.wait(wait_slice(std::clamp<std::chrono::microseconds>(
            left, 0us, std::chrono::duration_cast<std::chrono::microseconds>(kPollSlice))));
      }
    }
    NumericalStatus status = NumericalStatus::kOk;
    const auto [from, to] = fusion_.settle(status);
    if (status != NumericalStatus::kOk) {
      throw std::runtime_error(fmt::format("settling the last rounds: {}", to_string(status)));
    }
    for (std::uint64_t s = from; s < to; ++s) {
      io_.tracks.write(fusion_.settled_track(options_.node.run_id, s, me_.id));
    }
    io_.tracks.wait_acknowledged(2s);  // before FINISHED: the harness stops reading then
    return -1;
  }

  const StationOptions& options_;
  const RunPlan& plan_;
  const StationConfig& me_;
  std::unique_ptr<SensorSource<Sensor>> source_;
  transport::DdsNode node_;
  transport::NodePresence presence_;
  StationEndpoints io_;
  Fusion fusion_;
  Sensor sensor_;
  Covariance<Sensor::kMeasDim> noise_;
  std::uint64_t epoch_ns_ = 0;  // real time: the system-clock start of step 0
  bool syncing_;                // restarted, and no peer's prior taken yet
  std::uint64_t lost_ = 0;      // increments removed by the simulated loss
  std::uint32_t resyncs_ = 0;   // rounds fused onto another station's prior
  transport::SourceBinding sources_;
  transport::DelayedInbox<wire::InformationIncrement> delayed_;  // held by --link-delay-ms
  DropTally drops_;
};

// Runs station `me` with its sensor of type Sensor, on the run's motion model and filter.
template <typename Model, typename Sensor>
int run_with_sensor(const StationOptions& options, const RunPlan& plan, const StationConfig& me) {
  std::unique_ptr<SensorSource<Sensor>> source;
  if (options.replay_path.empty()) {
    source = std::make_unique<SimulatedSensor<Sensor>>(plan, me);
  } else {
    source = std::make_unique<ReplayedSensor<Sensor>>(options.replay_path, me.id);
  }
  // The round rule screens every value this station reports; its noise and site, fixed for the
  // run, are checked here once.
  if (const auto why = check_observation_source(
          make_sensor<Sensor>(me),
          station_noise_covariance<Sensor::kMeasDim>(plan.scenario, me, plan.mc_run))) {
    throw std::invalid_argument(
        fmt::format("station {}: its noise or site is unusable: {}", me.id, to_string(*why)));
  }
  int code = options::kExitError;
  visit_filter_kind<FilterParts>(
      plan.scenario.filter.kind, [&]<typename Filter>(std::type_identity<Filter>) {
        // The loader gives a filter only the models and stations it runs on.
        if constexpr (filter_runs_on<Filter, Model, Sensor>()) {
          Station<Sensor, typename StationFusionOf<Filter, Model, Sensor>::type> station(
              options, plan, me, std::move(source));
          code = station.run();
        } else {
          throw std::logic_error(fmt::format("filter {} on {} with a station of sensor kind {}",
                                             Filter::kKind, Model::kKind, me.sensor.kind));
        }
      });
  return code;
}

}  // namespace

int run_station(const StationOptions& options) {
  const RunPlan plan = transport::load_plan(options.node);
  const StationConfig* me = plan.participant(options.id);
  if (me == nullptr) {
    throw std::invalid_argument(fmt::format(
        "--id: station {} is not one of the {} participating stations of scenario '{}' (ids {})",
        options.id, plan.stations, plan.scenario.name, fmt::join(plan.participant_ids(), ", ")));
  }
  if (options.rejoin_step) {
    if (*options.rejoin_step >= static_cast<std::uint64_t>(plan.scenario.steps)) {
      throw std::invalid_argument(fmt::format("--rejoin-at-step: {} is past the run's last step {}",
                                              *options.rejoin_step, plan.scenario.steps - 1));
    }
    if (options.node.realtime_deadline_ms > 0.0) {
      throw std::invalid_argument("--rejoin-at-step: lock-step runs only, not real time");
    }
  }
  int code = options::kExitError;
  bool found = false;
  visit_model_kind<MotionModels>(
      plan.scenario.filter.motion_model.kind, [&]<typename Model>(std::type_identity<Model>) {
        found = visit_sensor_kind<Sensors, Model::kDim>(
            me->sensor.kind, [&]<template <int> class SensorOf>(SensorTemplate<SensorOf>) {
              code = run_with_sensor<Model, SensorOf<Model::kDim>>(options, plan, *me);
            });
      });
  if (!found) {
    throw std::logic_error(fmt::format("unregistered motion model {} or sensor kind {}",
                                       plan.scenario.filter.motion_model.kind, me->sensor.kind));
  }
  return code;
}

}  // namespace skyfuse::station
