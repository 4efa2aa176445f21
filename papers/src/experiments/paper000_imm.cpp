#include "skyfuse/experiments/paper000_imm.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "skyfuse/metrics/nees.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/registry/sensor_pack.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/scenario/truth.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
// Its own IMMs (one mode, and the paper's sets) run with its radars: compiled here, since no
// configuration group of the registry holds the one-mode IMM.
#include "skyfuse/tracking/imm_network_impl.hpp"

namespace skyfuse {
namespace {

using Radar = RangeAzimuthElevation<9>;
using Peers = NetworkPeerImm;
using Central = NetworkCentralImm;
using CaOnly = PeerImm<KinematicState, ConstantAcceleration3D>;

// The network's measurements of one step: one observation per station, ascending id.
struct Network {
  std::vector<StationObservation<Radar>> observations;

  Network(const Scenario& scenario, int stations, std::uint64_t run) {
    if (stations < 1 || stations > static_cast<int>(scenario.stations.size())) {
      throw std::invalid_argument("network IMM: station count outside the scenario's");
    }
    for (int i = 0; i < stations; ++i) {
      const StationConfig& s = scenario.stations[static_cast<std::size_t>(i)];
      observations.push_back(make_observation<Radar>(scenario, s, run));
    }
    std::sort(observations.begin(), observations.end(),
              [](const auto& a, const auto& b) { return a.station_id < b.station_id; });
  }

  void measure(const Scenario& scenario, const Vector<9>& truth, std::uint64_t run,
               std::size_t step) {
    for (auto& o : observations) {
      o.z = simulate_measurement(o.sensor, truth, o.noise, scenario.seed, run, o.station_id, step);
    }
  }
};

// One round of peers: each computes its contribution, every peer fuses all of them. (The
// predict that ends a round is the caller's, after it has read the posteriors.)
template <typename PeerFilter>
void fuse_round(std::vector<PeerFilter>& peers, const Network& network) {
  std::vector<typename PeerFilter::Contribution> contributions(network.observations.size());
  for (std::size_t i = 0; i < network.observations.size(); ++i) {
    // Station i computes its own; it holds the same prior as every other peer.
    const OwnContribution own =
        peers[i % peers.size()].contribute(network.observations[i], NisGate{}, contributions[i]);
    if (own.status != NumericalStatus::kOk) throw NumericalError("network IMM: increment failed");
  }
  std::vector<const typename PeerFilter::Contribution*> pointers;
  for (const auto& c : contributions) pointers.push_back(&c);
  const std::vector<double> weights(contributions.size(), 1.0);
  for (PeerFilter& peer : peers) {
    if (peer.fuse_round(pointers, weights).status != NumericalStatus::kOk) {
      throw NumericalError("network IMM: fusion failed");
    }
  }
}

// NEES of [p; v], the components the CA filter and the IMM's mixture both estimate.
double position_velocity_nees(const Vector<9>& truth, const Vector<10>& mean,
                              const Covariance<10>& covariance) {
  return nees<6>(truth.head<6>(),
                 GaussianState<6>{mean.head<6>(), covariance.topLeftCorner<6, 6>()});
}

template <typename Filter>
bool same_bits(const Filter& a, const Filter& b) {
  bool same = a.mode_probabilities() == b.mode_probabilities();
  [&]<int... I>(std::integer_sequence<int, I...>) {
    ((same = same && a.template mode_state<I>().mean == b.template mode_state<I>().mean &&
             a.template mode_state<I>().covariance == b.template mode_state<I>().covariance),
     ...);
  }
  (std::make_integer_sequence<int, Filter::kModes>{});
  return same;
}

}  // namespace

CentralPeerComparison compare_central_and_peers(const Scenario& scenario, double speed_mps,
                                                int stations, std::uint64_t run, int steps) {
  const TruthTrajectory truth =
      generate_truth(scenario.target, speed_mps, scenario.time_step_s, steps);
  const GaussianState<9> start =
      initial_estimate<ConstantAcceleration3D>(scenario, truth.states[0], run);
  Central central(NetworkImm<DefaultImmModes>::make(scenario, start));
  std::vector<Peers> peers(static_cast<std::size_t>(stations),
                           Peers(NetworkImm<DefaultImmModes>::make(scenario, start)));
  Network network(scenario, stations, run);

  CentralPeerComparison out;
  for (int k = 0; k < steps; ++k) {
    const auto step = static_cast<std::size_t>(k);
    network.measure(scenario, truth.states[step], run, step);
    if (central.update(std::span<const StationObservation<Radar>>(network.observations)) !=
        NumericalStatus::kOk) {
      throw NumericalError("network IMM: central update failed");
    }
    fuse_round(peers, network);

    const NetworkImmFilter& peer = peers.front().filter();
    const Vector3 p_central = central.filter().estimate().mean.head<3>();
    const Vector3 p_peer = peer.estimate().mean.head<3>();
    out.max_position_difference_m =
        std::max(out.max_position_difference_m, (p_central - p_peer).cwiseAbs().maxCoeff());
    out.max_probability_difference = std::max(
        out.max_probability_difference,
        (central.filter().mode_probabilities() - peer.mode_probabilities()).cwiseAbs().maxCoeff());
    for (const Peers& other : peers)
      out.peers_identical = out.peers_identical && same_bits(other.filter(), peer);
    out.final_probabilities = peer.mode_probabilities();
    ++out.steps;
    central.predict();
    for (Peers& p : peers) p.predict();
  }
  return out;
}

TurnComparison imm_against_ca(const Scenario& scenario, double speed_mps, int stations, int runs) {
  const TruthTrajectory truth =
      generate_truth(scenario.target, speed_mps, scenario.time_step_s, scenario.steps);
  const auto steps = static_cast<std::size_t>(scenario.steps);
  TurnComparison out;
  out.rmse_ca_m.assign(steps, 0.0);
  out.rmse_imm_m.assign(steps, 0.0);
  out.anees_ca.assign(steps, 0.0);
  out.anees_imm.assign(steps, 0.0);
  out.mean_probabilities.assign(steps, Vector3::Zero());
  for (std::size_t k = 0; k < steps; ++k)
    out.time_s.push_back(static_cast<double>(k) * scenario.time_step_s);

  for (int r = 0; r < runs; ++r) {
    const auto run = static_cast<std::uint64_t>(r);
    const GaussianState<9> start =
        initial_estimate<ConstantAcceleration3D>(scenario, truth.states[0], run);
    std::vector<Peers> imm{Peers(NetworkImm<DefaultImmModes>::make(scenario, start))};
    std::vector<CaOnly> ca{
        CaOnly(CaOnly::Filter({network_imm_ca_model(scenario)}, Matrix<1, 1>::Identity(),
                              Vector<1>::Ones(), network_imm_start(start, 1.0)))};
    Network network(scenario, stations, run);
    for (std::size_t k = 0; k < steps; ++k) {
      network.measure(scenario, truth.states[k], run, k);
      fuse_round(imm, network);
      fuse_round(ca, network);
      const NetworkImmFilter::CommonState imm_posterior = imm.front().filter().estimate();
      const NetworkImmFilter::CommonState ca_posterior = ca.front().filter().estimate();
      const Vector<9>& x = truth.states[k];
      out.rmse_imm_m[k] += (imm_posterior.mean.head<3>() - x.head<3>()).squaredNorm();
      out.rmse_ca_m[k] += (ca_posterior.mean.head<3>() - x.head<3>()).squaredNorm();
      out.anees_imm[k] += position_velocity_nees(x, imm_posterior.mean, imm_posterior.covariance);
      out.anees_ca[k] += position_velocity_nees(x, ca_posterior.mean, ca_posterior.covariance);
      out.mean_probabilities[k] += imm.front().filter().mode_probabilities();
      imm.front().predict();
      ca.front().predict();
    }
  }
  for (std::size_t k = 0; k < steps; ++k) {
    out.rmse_imm_m[k] = std::sqrt(out.rmse_imm_m[k] / runs);
    out.rmse_ca_m[k] = std::sqrt(out.rmse_ca_m[k] / runs);
    out.anees_imm[k] /= runs;
    out.anees_ca[k] /= runs;
    out.mean_probabilities[k] /= runs;
  }
  return out;
}

}  // namespace skyfuse
