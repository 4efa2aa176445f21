#pragma once
/// \file
/// Everything random about a run, each a pure function of (seed, run, station, step): the
/// station noise scales, the simulated measurements and the filter's initial estimate. A station
/// process and the in-process sweep call these same functions and so see the same numbers.

#include <cmath>
#include <cstdint>

#include "skyfuse/core/types.hpp"
#include "skyfuse/random/counter_rng.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {

/// The variance scale s_i of station `station_id` in Monte-Carlo run `run`; always >= floor > 0
/// under the paper model (see NoiseScaleConfig).
double draw_noise_scale(const NoiseScaleConfig& config, std::uint64_t seed, std::uint64_t run,
                        int station_id);

/// R_i = s_i * diag(noise_std^2) for the station's sensor in this run (sized by the sensor).
Eigen::MatrixXd station_noise_covariance(const Scenario& scenario, const StationConfig& station,
                                         std::uint64_t run);

/// The same, as the fixed-size matrix of a sensor with M components.
template <int M>
Covariance<M> station_noise_covariance(const Scenario& scenario, const StationConfig& station,
                                       std::uint64_t run) {
  return Covariance<M>(station_noise_covariance(scenario, station, run));
}

/// z = h(x) + nu with nu ~ N(0, R) (R diagonal), as the sensor reports it (to_reported: e.g.
/// angles wrapped). The sensor sees the target's true kinematics x = [p; v; a], so `Sensor` is
/// a sensor of the 9-entry kinematic state whatever the filter's model.
template <typename Sensor>
typename Sensor::Measurement simulate_measurement(const Sensor& sensor,
                                                  const Vector<kKinematicsDim>& truth,
                                                  const Covariance<Sensor::kMeasDim>& noise,
                                                  std::uint64_t seed, std::uint64_t run,
                                                  int station_id, std::uint64_t step) {
  static_assert(Sensor::kStateDim == 9, "measurements are simulated from the true kinematics");
  CounterRng rng(
      {seed, run, static_cast<std::uint64_t>(station_id), step, NoiseStream::kMeasurement});
  typename Sensor::Measurement z = sensor.predict(truth);
  for (int i = 0; i < Sensor::kMeasDim; ++i) z(i) += std::sqrt(noise(i, i)) * rng.normal();
  return Sensor::to_reported(z);
}

/// The error e of the filter's initial estimate: fixed by the scenario, or drawn from N(0, P0)
/// (one entry per state component of the scenario's motion model).
Eigen::VectorXd initial_state_error(const Scenario& scenario, std::uint64_t run);

/// The filter's start x0_hat = x0 + e, P0, with x0 the model's state of the true kinematics.
/// A model whose state carries a range derived from its position (paper 002's relative state,
/// d_t1 = |dp|) derives the estimate's from the estimate's own position, rates and
/// accelerations: e's entries for it are not used.
template <typename Model>
GaussianState<Model::kDim> initial_estimate(const Scenario& scenario,
                                            const Vector<kKinematicsDim>& true_initial_state,
                                            std::uint64_t run) {
  GaussianState<Model::kDim> estimate;
  estimate.covariance = scenario.filter.initial_covariance_diag.asDiagonal();
  estimate.mean = Model::from_kinematics(true_initial_state);
  estimate.mean += initial_state_error(scenario, run);
  if constexpr (requires { Model::with_derived_range(estimate.mean); }) {
    estimate.mean = Model::with_derived_range(estimate.mean);
  }
  return estimate;
}

}  // namespace skyfuse
