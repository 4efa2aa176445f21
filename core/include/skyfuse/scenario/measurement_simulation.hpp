#pragma once
/// \file
/// Everything random about a run, each a pure function of (seed, run, station, step): the
/// station noise scales, the simulated measurements and the filter's initial estimate. A station
/// process and the in-process sweep call these same functions and so see the same numbers.

#include <cstdint>

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

using StationSensor = RangeAzimuthElevation<9>;

/// The variance scale s_i of station `station_id` in Monte-Carlo run `run`; always >= floor > 0
/// under the paper model (see NoiseScaleConfig).
double draw_noise_scale(const NoiseScaleConfig& config, std::uint64_t seed, std::uint64_t run,
                        int station_id);

/// R_i = s_i * diag(noise_std^2) for the station in this run.
Covariance<3> station_noise_covariance(const Scenario& scenario, const StationConfig& station,
                                       std::uint64_t run);

/// z = h(p) + nu with nu ~ N(0, R) (R diagonal), azimuth wrapped into (-pi, pi], elevation
/// held within [-pi/2, pi/2] (past the zenith a sensor reports the zenith).
Vector3 simulate_measurement(const StationSensor& sensor, const Vector3& true_position,
                             const Covariance<3>& noise, std::uint64_t seed, std::uint64_t run,
                             int station_id, std::uint64_t step);

/// The filter's start: x0_hat = x0 + e with e fixed by the scenario or drawn from N(0, P0).
GaussianState<9> initial_estimate(const Scenario& scenario, const Vector<9>& true_initial_state,
                                  std::uint64_t run);

}  // namespace skyfuse
