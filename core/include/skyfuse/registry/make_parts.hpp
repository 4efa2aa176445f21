#pragma once
/// \file
/// Builds the typed parts a scenario names: the motion model with its process noise, and a
/// station's sensor at its site.

#include <algorithm>
#include <span>
#include <stdexcept>

#include "skyfuse/models/height_band.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {

template <typename Model>
Model make_motion_model(const Scenario& scenario) {
  const Eigen::VectorXd& values = scenario.filter.motion_model.process_noise_std;
  typename Model::NoiseStd noise_std{};
  if (static_cast<std::size_t>(values.size()) != noise_std.size() ||
      scenario.filter.motion_model.kind != Model::kKind) {
    throw std::invalid_argument("the scenario's motion model is not " + std::string(Model::kKind));
  }
  std::copy(values.begin(), values.end(), noise_std.begin());
  return Model(scenario.time_step_s, noise_std);
}

namespace detail {
template <typename Sensor, int M>
struct AtStateDim;
template <template <int> class Sensor, int N, int M>
struct AtStateDim<Sensor<N>, M> {
  using type = Sensor<M>;
};
}  // namespace detail

/// The same sensor as it measures the truth's kinematics (truth.hpp): what simulates a station's
/// measurements, whatever state the filter keeps.
template <typename Sensor>
using TruthSensorOf = typename detail::AtStateDim<Sensor, kKinematicsDim>::type;

/// A sensor of several receivers: the scenario lists those beside its site.
template <typename Sensor>
concept HasOtherReceivers = requires {
  Sensor::kReceivers;
};
/// Whether a sensor takes more from the scenario than its site. Such a sensor is rebuilt from
/// the scenario wherever it is received, never from its site alone.
template <typename Sensor>
concept ConfiguredByScenario =
    HasOtherReceivers<Sensor> || TakesHeightBand<Sensor>;  // models/height_band.hpp

/// Station `station`'s sensor standing at `site`: for a sensor of several receivers, with the
/// others' sites and its components' nominal noise from the scenario
/// (models/multilateration.hpp); for a sensor that measures no height, with the heights it
/// assumes (models/range_azimuth.hpp).
template <typename Sensor>
Sensor make_sensor_at(const Vector3& site, const StationConfig& station) {
  if constexpr (TakesHeightBand<Sensor>) {
    return Sensor(site, station.sensor.height_band_m.value());
  } else if constexpr (HasOtherReceivers<Sensor>) {
    const Eigen::VectorXd& noise_std = station.sensor.noise_std;
    return Sensor(
        site, station.sensor.receivers_m,
        std::span<const double>(noise_std.data(), static_cast<std::size_t>(noise_std.size())));
  } else {
    return Sensor(site);
  }
}

/// A station's sensor, at its site.
template <typename Sensor>
Sensor make_sensor(const StationConfig& station) {
  return make_sensor_at<Sensor>(station.position_m, station);
}

}  // namespace skyfuse
