#pragma once
// The typed side of a station's sensing (station_sensing.hpp): a sensor of one kind, its source
// and the filter part's contribution rule, compiled per shard of the configuration groups in
// sensing_shard.cpp, with no DDS code in sight.

#include <fmt/format.h>

#include <limits>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "sensor_source.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/tracking/increment_rules.hpp"
#include "skyfuse/tracking/tdoa_round.hpp"
#include "skyfuse/transport/wire_conversion.hpp"
#include "skyfuse/validation/sample_checks.hpp"
#include "station_sensing.hpp"

namespace skyfuse::station {
namespace detail {

/// The NCRKF's contribution: it has no innovation to screen (its part refuses a NIS gate) and
/// no prior in its increment, which depends on the receiver's measurement and site only; a
/// measurement its sensor could not report yields a zero increment, which tells the peers not
/// to wait for one.
struct TdoaContributionRule {
  template <int N>
  static OwnContribution contribute(const GaussianState<N>& /*prior*/,
                                    const StationObservation<RangeDifferenceSensor<N>>& observation,
                                    const NisGate& /*gate*/, InformationIncrement<N>& out) {
    OwnContribution result;
    result.refused = RangeDifferenceSensor<N>::check_reported(observation.z);
    if (result.refused) {
      out.set_zero(observation.station_id);
    } else {
      out = tdoa_contribution(observation);
    }
    return result;
  }
};

/// The IMM's: every mode's increment against its own prior, mixed by the peer.
struct ImmContributionRule {
  template <typename Peer, typename Observation>
  static OwnContribution contribute(const Peer& peer, const Observation& observation,
                                    const NisGate& gate, typename Peer::Contribution& out) {
    return peer.contribute(observation, gate, out);
  }
};

/// What turns a station's measurement into its contribution, per filter part: its increment
/// rule (tracking/increment_rules.hpp) if it has one.
template <typename Filter>
struct ContributionRuleOf {
  using type = typename Filter::IncrementRule;
};
template <typename ModeSet>
struct ContributionRuleOf<ImmFilterPart<ModeSet>> {
  using type = ImmContributionRule;
};
template <>
struct ContributionRuleOf<NcrkfFilterPart> {
  using type = TdoaContributionRule;
};

/// A station with a `Sensor`, its `source` and `Rule`, as the fusion's `Interface`.
template <typename Interface, typename Sensor, typename Rule>
class SensorSensing final : public Interface {
 public:
  SensorSensing(const RunPlan& plan, const StationConfig& me,
                std::unique_ptr<SensorSource<Sensor>> source)
      : source_(std::move(source)),
        observation_{me.id, make_sensor<Sensor>(me),
                     Vector<Sensor::kMeasDim>::Constant(std::numeric_limits<double>::quiet_NaN()),
                     station_noise_covariance<Sensor::kMeasDim>(plan.scenario, me, plan.mc_run)} {
    // The round rule screens every value this station reports; its noise and site, fixed for
    // the run, are checked here once.
    if (const auto why = check_observation_source(observation_.sensor, observation_.noise)) {
      throw std::invalid_argument(
          fmt::format("station {}: its noise or site is unusable: {}", me.id, to_string(*why)));
    }
  }

  int station_id() const override { return observation_.station_id; }

  wire::Measurement measure(std::uint64_t k, std::uint64_t run_id) override {
    observation_.z = source_->measurement(k);
    return transport::to_wire(observation_, run_id, static_cast<std::uint32_t>(k));
  }

  OwnContribution contribute(const typename Interface::Against& prior, const NisGate& gate,
                             typename Interface::Contribution& out) const override {
    return Rule::contribute(prior, observation_, gate, out);
  }

 private:
  std::unique_ptr<SensorSource<Sensor>> source_;
  StationObservation<Sensor> observation_;
};

template <typename Filter, typename Model, typename Sensor>
std::unique_ptr<AnyStationSensing> make_sensing(const StationOptions& options, const RunPlan& plan,
                                                const StationConfig& me) {
  std::unique_ptr<SensorSource<Sensor>> source;
  if (options.replay_path.empty()) {
    source = std::make_unique<SimulatedSensor<Sensor>>(plan, me);
  } else {
    source = std::make_unique<ReplayedSensor<Sensor>>(options.replay_path, me.id);
  }
  using Interface = typename SensingOf<Filter, Model>::type;
  using Rule = typename ContributionRuleOf<Filter>::type;
  return std::make_unique<SensorSensing<Interface, Sensor, Rule>>(plan, me, std::move(source));
}

}  // namespace detail

template <std::size_t Shard>
std::unique_ptr<AnyStationSensing> make_sensing_in_shard(const StationOptions& options,
                                                         const RunPlan& plan,
                                                         const StationConfig& me) {
  std::unique_ptr<AnyStationSensing> sensing;
  visit_group_in_shard<Shard>(plan.scenario.filter, [&]<typename Filter, typename Model>(
                                                        std::type_identity<Filter>,
                                                        std::type_identity<Model>) {
    const bool found = visit_sensor_kind<Sensors, Model::kDim>(
        me.sensor.kind, [&]<template <int> class SensorOf>(SensorTemplate<SensorOf>) {
          using Sensor = SensorOf<Model::kDim>;
          // The loader gives a filter only the stations it runs on.
          if constexpr (filter_runs_on<Filter, Model, Sensor>()) {
            sensing = detail::make_sensing<Filter, Model, Sensor>(options, plan, me);
          } else {
            throw std::logic_error(fmt::format("filter {} on {} with a station of sensor kind {}",
                                               Filter::kKind, Model::kKind, me.sensor.kind));
          }
        });
    if (!found) {
      throw std::logic_error(
          fmt::format("station {}: unregistered sensor kind {}", me.id, me.sensor.kind));
    }
  });
  return sensing;
}

}  // namespace skyfuse::station
