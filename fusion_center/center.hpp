#pragma once
// The center's rounds, compiled for the filter parts of one shard at a time
// (registry/filter_shards.hpp): center_shard.cpp instantiates run_center_in_shard once per
// shard. center_process.cpp, which only declares it, picks the shard of the run's filter.

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <optional>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "center_process.hpp"
#include "center_shards.hpp"
#include "central_fusion.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/tracking/fixed_lag_center.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/node_loop.hpp"
#include "skyfuse/transport/node_setup.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "skyfuse/transport/wire_conversion.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse::center {
namespace detail {

using transport::RunEnd;

// The center for stations of `Sensor` (one sensor type, or a SensorPack when they differ),
// whose rounds `Fusion` updates: what the run's filter part runs at the center
// (central_fusion.hpp, CenterFusionOf), in the fixed-lag chain (tracking/fixed_lag_center.hpp).
// The round loop (transport/node_loop.hpp) moves the samples; this is what the center adds.
template <typename Sensor, typename Fusion>
class Center {
 public:
  using Observation = ObservationFor<Sensor>;

  // The endpoints are made in a fixed order: the loop's tick and measurement readers first.
  // (load_plan refuses a lag for a fusion that takes none.)
  Center(const options::NodeOptions& options, const RunPlan& plan)
      : options_(options),
        plan_(plan),
        node_(transport::node_config(options, "skyfuse-center")),
        loop_(node_, options, kCenterSourceId, "a fusion center", "measurement",
              plan.scenario.time_step_s),
        tracks_(node_.make_writer<wire::TrackEstimate>()),
        chain_(Fusion(plan), plan.participant_ids(), options.refusion_lag),
        final_tracks_(options.refusion_lag + 1) {}

  int run() {
    const int m = plan_.stations;
    auto& measurements = loop_.inputs();
    auto& ticks = loop_.ticks();
    if (const RunEnd end = loop_.join(
            [&] {
              return measurements.matched() >= m && ticks.matched() >= 1 && tracks_.matched() >= 1;
            },
            [&] {
              return fmt::format("measurement writers {}/{}, tick writer {}/1, track readers {}/1",
                                 measurements.matched(), m, ticks.matched(), tracks_.matched());
            })) {
      return *end;
    }
    spdlog::info("joined run {} with {} stations", options_.run_id, m);
    const int code = loop_.run(*this, 0, static_cast<std::uint64_t>(plan_.scenario.steps), tracks_);
    if constexpr (requires { chain_.fusion().report(); }) chain_.fusion().report();
    return code;
  }

  // What the round loop asks of the center (transport::NodeProcess).

  RunEnd open_round(std::uint64_t /*k*/) { return std::nullopt; }  // it measures nothing

  // Checks a received measurement (garbage whoever sent it; then who it claims to be and when;
  // then whether the writer really speaks for that station) and keeps it.
  std::optional<DropKind> receive(const wire::Measurement& sample,
                                  const transport::WriterId& writer) {
    const auto received = transport::observation_for<Sensor>(sample);
    if (!received) return DropKind::kOutOfRange;  // another sensor kind, or other lengths
    const Observation& observation = *received;
    // An unknown id is left to admit(), which says so.
    const StationConfig* station = plan_.participant(sample.station_id());
    if (const auto why = with_observation(
            observation, [&](const auto& o) { return check_station_measurement(o, station); })) {
      return why;
    }
    const auto why = transport::admit(chain_.collector(), sources_, sample.step(),
                                      sample.station_id(), writer, observation);
    if (!why) chain_.kept(sample.step());
    return why;
  }

  bool round_complete() const { return chain_.collector().complete(); }

  // Updates round k with the measurements that arrived, screened and stacked by the round
  // rule as the in-process twin does, so both compute the same bits (and, with a re-fusion
  // lag, the rounds late measurements came for again); publishes its track and the one that
  // leaves the lag.
  RunEnd close_round(std::uint64_t k) {
    const NumericalStatus status = chain_.close_round(
        options_.nis_gate(),
        [&](int station_id, DropKind why) { loop_.count_drop(why, station_id, k); },
        [&](std::uint64_t q) { keep_track(q); });
    if (status != NumericalStatus::kOk) {
      return loop_.fail(k, fmt::format("step {}: stacked update failed: {}", k, to_string(status)),
                        options::kExitNumerical);
    }
    tracks_.write(track_of(k));
    if (const auto settled = chain_.settled_round()) tracks_.write(settled_track(*settled));
    chain_.advance();
    return std::nullopt;
  }

  // After the last round, with a re-fusion lag: the rounds late measurements came for updated
  // again, and the final tracks of the rounds still in the lag.
  RunEnd settle(std::uint64_t steps) {
    NumericalStatus status = NumericalStatus::kOk;
    const auto [from, to] = chain_.settle_rest(
        options_.nis_gate(), [&](std::uint64_t q) { keep_track(q); }, status);
    if (status != NumericalStatus::kOk) {
      return loop_.fail(
          steps,
          fmt::format("settling the last rounds: stacked update failed: {}", to_string(status)),
          options::kExitNumerical);
    }
    for (std::uint64_t s = from; s < to; ++s) tracks_.write(settled_track(s));
    return std::nullopt;
  }

  transport::ProcessCounts counts() const { return {0, chain_.late_used()}; }

 private:
  // Each round's latest track while it is in the lag: made when the round is updated.
  void keep_track(std::uint64_t q) {
    final_tracks_[q % final_tracks_.size()] =
        chain_.fusion().track(options_.run_id, q, kCenterSourceId);
  }
  const wire::TrackEstimate& track_of(std::uint64_t q) const {
    return final_tracks_[q % final_tracks_.size()];
  }
  // Round `step`'s final estimate, as it leaves the lag.
  wire::TrackEstimate settled_track(std::uint64_t step) const {
    wire::TrackEstimate track = track_of(step);
    track.settled(true);
    return track;
  }

  const options::NodeOptions& options_;
  const RunPlan& plan_;
  transport::DdsNode node_;
  transport::NodeLoop<wire::Measurement> loop_;
  transport::Writer<wire::TrackEstimate> tracks_;
  FixedLagCenter<Fusion, Observation> chain_;
  std::vector<wire::TrackEstimate> final_tracks_;
  transport::SourceBinding sources_;
};

}  // namespace detail

template <std::size_t Shard>
int run_center_in_shard(const options::NodeOptions& options, const RunPlan& plan) {
  int code = options::kExitError;
  dispatch_configuration(
      plan.scenario, plan.stations,
      [&]<typename Model, template <int> class SensorOf>(std::type_identity<Model>,
                                                         SensorTemplate<SensorOf>) {
        using Sensor = SensorOf<Model::kDim>;
        visit_filter_in_shard<Shard>(plan.scenario.filter, [&]<typename Filter>(
                                                               std::type_identity<Filter>) {
          // The loader gives a filter only the models and stations it runs on.
          if constexpr (filter_runs_on<Filter, Model, Sensor>()) {
            using Fusion = typename CenterFusionOf<Filter, Model, Sensor>::type;
            code = transport::make_lifelong<detail::Center<Sensor, Fusion>>(options, plan).run();
          } else {
            throw std::logic_error(
                fmt::format("filter {} on {} with these stations", Filter::kKind, Model::kKind));
          }
        });
      });
  return code;
}

}  // namespace skyfuse::center
