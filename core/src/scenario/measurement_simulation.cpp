#include "skyfuse/scenario/measurement_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "skyfuse/core/angles.hpp"
#include "skyfuse/random/counter_rng.hpp"

namespace skyfuse {

double draw_noise_scale(const NoiseScaleConfig& config, std::uint64_t seed, std::uint64_t run,
                        int station_id) {
  if (config.model == NoiseScaleConfig::Model::kNone) return 1.0;
  // Truncated normal by rejection: a draw fails with P(1 + delta < floor) = Phi(floor - 1),
  // at most 0.5 for the floors the loader accepts (<= 1), so all 200 draws fail with
  // probability at most 0.5^200 ~ 6e-61 (0.18^200 ~ 1e-147 at the default floor 0.1). The
  // fallback keeps the contract (a positive scale) even then.
  CounterRng rng({seed, run, static_cast<std::uint64_t>(station_id), 0, NoiseStream::kNoiseScale});
  for (int attempt = 0; attempt < 200; ++attempt) {
    const double scale = 1.0 + rng.normal();
    if (scale >= config.floor) return scale;
  }
  return config.floor;
}

Covariance<3> station_noise_covariance(const Scenario& scenario, const StationConfig& station,
                                       std::uint64_t run) {
  const double scale = draw_noise_scale(scenario.noise_scale, scenario.seed, run, station.id);
  return (scale * station.noise_std.array().square()).matrix().asDiagonal();
}

Vector3 simulate_measurement(const StationSensor& sensor, const Vector3& true_position,
                             const Covariance<3>& noise, std::uint64_t seed, std::uint64_t run,
                             int station_id, std::uint64_t step) {
  CounterRng rng(
      {seed, run, static_cast<std::uint64_t>(station_id), step, NoiseStream::kMeasurement});
  Vector3 z = sensor.measure_position(true_position);
  for (int i = 0; i < 3; ++i) z(i) += std::sqrt(noise(i, i)) * rng.normal();
  z(StationSensor::kAzimuth) = wrap_angle(z(StationSensor::kAzimuth));
  // A sensor reports elevation within [-pi/2, pi/2]. Near the zenith the noise would carry it
  // past, and every receiver - the station itself, the center, the harness's recorder - would
  // refuse the measurement (check_reported_values).
  constexpr double kHalfPi = std::numbers::pi / 2.0;
  z(StationSensor::kElevation) = std::clamp(z(StationSensor::kElevation), -kHalfPi, kHalfPi);
  return z;
}

GaussianState<9> initial_estimate(const Scenario& scenario, const Vector<9>& true_initial_state,
                                  std::uint64_t run) {
  GaussianState<9> estimate;
  estimate.covariance = scenario.filter.initial_covariance_diag.asDiagonal();
  if (scenario.filter.initial_state_error) {
    estimate.mean = true_initial_state + *scenario.filter.initial_state_error;
    return estimate;
  }
  CounterRng rng({scenario.seed, run, 0, 0, NoiseStream::kInitialState});
  estimate.mean = true_initial_state;
  for (int i = 0; i < 9; ++i) {
    estimate.mean(i) += std::sqrt(scenario.filter.initial_covariance_diag(i)) * rng.normal();
  }
  return estimate;
}

}  // namespace skyfuse
