#pragma once
/// \file
/// A run whose stations carry different sensors (ground radars and the aircraft's own GPS): a
/// closed set of sensor templates for an N-entry state, the variant of their observations, and
/// the few calls that reach one observation's concrete sensor. A run of one sensor kind uses the
/// sensor itself, not a pack: the same calls then compile to direct ones.

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>

#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/registry/part_lists.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"

namespace skyfuse {

template <int N, template <int> class... S>
struct SensorPack {
  static constexpr int kStateDim = N;
  using Observation = std::variant<StationObservation<S<N>>...>;
  static constexpr int kMaxMeasDim = std::max({S<N>::kMeasDim...});
};

template <typename T>
struct IsSensorPack : std::false_type {};
template <int N, template <int> class... S>
struct IsSensorPack<SensorPack<N, S...>> : std::true_type {};

/// Every sensor of a SensorList, as a pack for an N-entry state.
template <int N, typename List>
struct PackOfList;
template <int N, template <int> class... S>
struct PackOfList<N, SensorList<S...>> {
  using type = SensorPack<N, S...>;
};

namespace detail {
template <typename Sensor>
struct ObservationType {
  using type = StationObservation<Sensor>;
};
template <int N, template <int> class... S>
struct ObservationType<SensorPack<N, S...>> {
  using type = typename SensorPack<N, S...>::Observation;
};
template <typename T>
struct IsVariant : std::false_type {};
template <typename... T>
struct IsVariant<std::variant<T...>> : std::true_type {};
}  // namespace detail

/// What a round of stations with `Sensor` (one sensor type, or a pack) holds per station.
template <typename Sensor>
using ObservationFor = typename detail::ObservationType<Sensor>::type;

/// The largest measurement a station of `Sensor` (or of any sensor of a pack) reports.
template <typename Sensor>
constexpr int max_measurement_dim() {
  if constexpr (IsSensorPack<Sensor>::value) {
    return Sensor::kMaxMeasDim;
  } else {
    return Sensor::kMeasDim;
  }
}

/// f(observation) on the concrete StationObservation<S> an observation (or a variant) holds.
template <typename Observation, typename F>
decltype(auto) with_observation(Observation& observation, F&& f) {
  if constexpr (detail::IsVariant<std::remove_const_t<Observation>>::value) {
    return std::visit(std::forward<F>(f), observation);
  } else {
    return std::forward<F>(f)(observation);
  }
}

/// The station's observation in Monte-Carlo run `run`: its sensor (of the kind the scenario
/// names) at its site, and its noise R; z zero.
template <typename Sensor>
ObservationFor<Sensor> make_observation(const Scenario& scenario, const StationConfig& station,
                                        std::uint64_t run) {
  const auto of = [&]<typename Concrete>(std::type_identity<Concrete>) {
    StationObservation<Concrete> o;
    o.station_id = station.id;
    o.sensor = make_sensor<Concrete>(station);
    o.z.setZero();
    o.noise = station_noise_covariance<Concrete::kMeasDim>(scenario, station, run);
    return o;
  };
  if constexpr (IsSensorPack<Sensor>::value) {
    return [&]<int N, template <int> class... S>(std::type_identity<SensorPack<N, S...>>) {
      ObservationFor<Sensor> out;
      const bool found =
          ((S<N>::kKind == station.sensor.kind ? (out = of(std::type_identity<S<N>>{}), true)
                                               : false) ||
           ...);
      if (!found) throw std::logic_error("unregistered sensor kind " + station.sensor.kind);
      return out;
    }
    (std::type_identity<Sensor>{});
  } else {
    return of(std::type_identity<Sensor>{});
  }
}

}  // namespace skyfuse
