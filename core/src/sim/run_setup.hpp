#pragma once
// What an in-process run sets up once, whatever its filter: the order of every round (its first
// M stations in ascending id, as indices into the scenario's stations, with their ids and
// fusion weights in that order), the stations' observations, and a trace with room for every
// step.

#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "skyfuse/models/state_position.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/registry/sensor_pack.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/tracking/peer_tracker.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse::run_setup {

/// Scenario indices of the first `stations` stations, in ascending station id.
inline std::vector<std::size_t> ascending(const Scenario& scenario, int stations) {
  std::vector<std::size_t> order(static_cast<std::size_t>(stations));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return scenario.stations[a].id < scenario.stations[b].id;
  });
  return order;
}

inline std::vector<int> ids(const Scenario& scenario, const std::vector<std::size_t>& order) {
  std::vector<int> out;
  for (std::size_t i : order) out.push_back(scenario.stations[i].id);
  return out;
}

inline std::vector<double> weights(const Scenario& scenario,
                                   const std::vector<std::size_t>& order) {
  std::vector<double> out;
  for (std::size_t i : order) out.push_back(scenario.stations[i].weight);
  return out;
}

/// The observations of the stations in `order`, their sources (noise, site) checked: the round
/// rule screens each value, but the source is fixed for the run and checked once, here.
template <typename Sensor>
std::vector<ObservationFor<Sensor>> checked_observations(const Scenario& scenario,
                                                         const std::vector<std::size_t>& order,
                                                         std::uint64_t run) {
  std::vector<ObservationFor<Sensor>> out;
  out.reserve(order.size());
  for (std::size_t i : order) {
    const StationConfig& station = scenario.stations[i];
    out.push_back(make_observation<Sensor>(scenario, station, run));
    const auto why = with_observation(
        out.back(), [](const auto& o) { return check_observation_source(o.sensor, o.noise); });
    if (why) {
      throw NumericalError(fmt::format("station {}: its noise or site is unusable: {}", station.id,
                                       to_string(*why)));
    }
  }
  return out;
}

/// Records step k's position errors of both tracks and their difference.
inline void record_positions(RunTrace& trace, std::size_t k, const Vector3& truth,
                             const Vector3& central, const Vector3& p2p) {
  trace.sq_error_central[k] = (truth - central).squaredNorm();
  trace.sq_error_p2p[k] = (truth - p2p).squaredNorm();
  trace.max_abs_diff_m = std::max(trace.max_abs_diff_m, (central - p2p).norm());
}

/// Records step k of a run whose peers hold a PeerTracker (truth x, the center's estimate, the
/// central NIS) and tells the observer. The NEES is against the peers' current covariance
/// (PeerTracker::normalized_squared_error: the fused information when the round fused).
template <typename Model>
void record_step(RunTrace& trace, std::size_t k, const Vector<kKinematicsDim>& x,
                 const GaussianState<Model::kDim>& central, const PeerTracker<Model>& peers,
                 double nis_central, const StepObserver& observer) {
  const Vector3 p_central = state_position<Model>(central.mean);
  const Vector3 p_p2p = state_position<Model>(peers.estimate().mean);
  record_positions(trace, k, state_position<Model>(Model::from_kinematics(x)), p_central, p_p2p);
  const Vector<Model::kDim> error = Model::from_kinematics(x) - peers.estimate().mean;
  trace.nees_p2p[k] = peers.normalized_squared_error(error);
  trace.nis_central[k] = nis_central;
  if (observer) {
    observer({static_cast<int>(k), x, EstimateView::of(central), EstimateView::of(peers.estimate()),
              nis_central, p_central, p_p2p});
  }
}

inline RunTrace sized_trace(int steps) {
  const auto n = static_cast<std::size_t>(steps);
  RunTrace trace;
  trace.sq_error_central.resize(n);
  trace.sq_error_p2p.resize(n);
  trace.nees_p2p.resize(n);
  trace.nis_central.resize(n);
  return trace;
}

}  // namespace skyfuse::run_setup
