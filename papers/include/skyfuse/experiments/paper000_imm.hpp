#pragma once
/// \file
/// Paper 000's IMM experiment: the network IMM (tracking/network_imm.hpp) on paper 000's
/// scenario, the central stacked IMM against the peers' fused one on the same measurements, and
/// the IMM against the paper's CA filter through the turn (RMSE and ANEES per step over
/// Monte-Carlo runs).
///
/// Each step k: every station measures the truth at k, the filters update, then predict. The
/// CA filter is the paper's (the scenario's process noise), which is also the IMM's CA mode.

#include <cstdint>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/tracking/network_imm.hpp"

namespace skyfuse {

/// Central stacked IMM against `stations` peers, each computing its own contribution and fusing
/// all of them, over one run.
struct CentralPeerComparison {
  int steps = 0;
  double max_position_difference_m = 0.0;  ///< central vs peer 0, over every step
  double max_probability_difference = 0.0;
  bool peers_identical = true;  ///< every peer's mode states and probabilities, bit for bit
  Vector3 final_probabilities = Vector3::Zero();  ///< peer 0's, [CV, CA, CT]
};
CentralPeerComparison compare_central_and_peers(const Scenario& scenario, double speed_mps,
                                                int stations, std::uint64_t run, int steps);

/// The IMM (fused by peers) against the CA filter, per step over `runs` runs.
struct TurnComparison {
  std::vector<double> time_s;
  std::vector<double> rmse_ca_m, rmse_imm_m;  ///< position RMSE over runs
  std::vector<double> anees_ca, anees_imm;    ///< NEES of [p; v] (6 dof), mean over runs
  std::vector<Vector3> mean_probabilities;    ///< the IMM's [CV, CA, CT], mean over runs
};
TurnComparison imm_against_ca(const Scenario& scenario, double speed_mps, int stations, int runs);

}  // namespace skyfuse
