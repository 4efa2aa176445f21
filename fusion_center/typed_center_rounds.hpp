#pragma once
// The center's rounds for stations of one `Sensor` (one sensor type, or a SensorPack when they
// differ) updated by `Fusion`: what the run's filter part runs at the center (central_fusion.hpp,
// CenterFusionOf), in the fixed-lag chain (tracking/fixed_lag_center.hpp). Compiled per shard of
// the configuration groups in center_rounds_shard.cpp, with no DDS code in sight; the center
// process (center.hpp) sees them as CenterRounds.

#include <fmt/format.h>

#include <memory>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "center_process.hpp"
#include "center_rounds.hpp"
#include "central_fusion.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/registry/sensor_parts.hpp"
#include "skyfuse/tracking/fixed_lag_center.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "skyfuse/transport/wire_conversion.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse::center {
namespace detail {

template <typename Sensor, typename Fusion>
class TypedCenterRounds final : public CenterRounds {
 public:
  using Observation = ObservationFor<Sensor>;

  // (load_any_plan refuses a lag for a fusion that takes none.)
  TypedCenterRounds(const options::NodeOptions& options, const RunPlan& plan)
      : run_id_(options.run_id),
        plan_(plan),
        chain_(Fusion(plan), plan.participant_ids(), options.refusion_lag),
        tracks_(options.refusion_lag + 1) {}

  std::optional<DropKind> receive(const wire::Measurement& sample,
                                  const transport::WriterId& writer) override {
    // An unknown id is left to admit(), which says so.
    const StationConfig* station = plan_.participant(sample.station_id());
    const auto received = transport::observation_for<Sensor>(sample, station);
    if (!received) return DropKind::kOutOfRange;  // another sensor kind, or other lengths
    const Observation& observation = *received;
    if (const auto why = with_observation(
            observation, [&](const auto& o) { return check_station_measurement(o, station); })) {
      return why;
    }
    const auto why = transport::admit(chain_.collector(), sources_, sample.step(),
                                      sample.station_id(), writer, observation);
    if (!why) chain_.kept(sample.step());
    return why;
  }

  bool round_complete() const override { return chain_.collector().complete(); }

  NumericalStatus close_round(const NisGate& gate, const OnRefused& on_refused) override {
    return chain_.close_round(gate, on_refused, [&](std::uint64_t q) { keep_track(q); });
  }

  const wire::TrackEstimate& track_of(std::uint64_t step) const override {
    return tracks_[step % tracks_.size()];
  }
  std::optional<std::uint64_t> settled_round() const override { return chain_.settled_round(); }
  void advance() override { chain_.advance(); }

  std::pair<std::uint64_t, std::uint64_t> settle_rest(const NisGate& gate,
                                                      NumericalStatus& status) override {
    return chain_.settle_rest(
        gate, [&](std::uint64_t q) { keep_track(q); }, status);
  }

  std::uint64_t late_used() const override { return chain_.late_used(); }

  void report() const override {
    if constexpr (requires { chain_.fusion().report(); }) chain_.fusion().report();
  }

 private:
  // Each round's latest track while it is in the lag: made when the round is updated.
  void keep_track(std::uint64_t q) {
    tracks_[q % tracks_.size()] = chain_.fusion().track(run_id_, q, kCenterSourceId);
  }

  std::uint64_t run_id_;
  const RunPlan& plan_;
  FixedLagCenter<Fusion, Observation> chain_;
  std::vector<wire::TrackEstimate> tracks_;
  transport::SourceBinding sources_;
};

}  // namespace detail

template <std::size_t Shard, std::size_t Part>
std::unique_ptr<CenterRounds> make_center_rounds_in_shard(const options::NodeOptions& options,
                                                          const RunPlan& plan) {
  std::unique_ptr<CenterRounds> rounds;
  visit_group_in_shard<Shard>(plan.scenario.filter, [&]<typename Filter, typename Model>(
                                                        std::type_identity<Filter>,
                                                        std::type_identity<Model>) {
    dispatch_sensor<Model::kDim>(
        plan.scenario, plan.stations, [&]<template <int> class SensorOf>(SensorTemplate<SensorOf>) {
          using Sensor = SensorOf<Model::kDim>;
          // The caller chose the part by with_sensor_part; the loader gives a filter only the
          // stations it runs on.
          if constexpr (!in_sensor_part<SensorOf, Part, kSensorPartsOf<Shard>>) {
            throw std::logic_error(
                fmt::format("sensor part {} of the center's shard {} holds no "
                            "'{}' stations",
                            Part, Shard, plan.scenario.stations.front().sensor.kind));
          } else if constexpr (filter_runs_on<Filter, Model, Sensor>()) {
            using Fusion = typename CenterFusionOf<Filter, Model, Sensor>::type;
            rounds = std::make_unique<detail::TypedCenterRounds<Sensor, Fusion>>(options, plan);
          } else {
            throw std::logic_error(
                fmt::format("filter {} on {} with these stations", Filter::kKind, Model::kKind));
          }
        });
  });
  return rounds;
}

}  // namespace skyfuse::center
