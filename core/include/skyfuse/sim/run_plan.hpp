#pragma once
/// \file
/// What one run is, for every process that takes part: the scenario (after command-line
/// overrides), which stations take part (the first M), at which speed, and which Monte-Carlo
/// run index selects the noise. Station, fusion center, harness and the in-process sweep build
/// the same plan from the same options, so they simulate the same run.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {

/// What a plan of either kind holds (one aircraft: RunPlan; many: PicturePlan,
/// sim/picture_plan.hpp; sim/any_plan.hpp decides which): the scenario after the overrides, how
/// many of its stations take part (the first `stations`), and the Monte-Carlo run index that
/// selects the noise.
struct CommonPlan {
  Scenario scenario;
  int stations = 0;
  std::uint64_t mc_run = 0;

  std::span<const StationConfig> participants() const {
    return std::span(scenario.stations).first(static_cast<std::size_t>(stations));
  }
  /// Ids of the participants, in scenario order.
  std::vector<int> participant_ids() const;
  /// The participant with this id, or nullptr.
  const StationConfig* participant(int station_id) const;
};

/// One aircraft's plan: the speed it flies at, and where the filters start.
struct RunPlan : CommonPlan {
  double speed_mps = 0.0;

  /// The fusion weights of the participants `ids`, in that order.
  std::vector<double> weights_of(std::span<const int> ids) const;
  TruthTrajectory truth() const {
    return generate_truth(scenario.target, speed_mps, scenario.time_step_s, scenario.steps);
  }
  /// The target's true kinematics [p; v; a] at step 0.
  Vector<kKinematicsDim> true_initial_state() const;
  /// The filter's motion model (the scenario's, as type `Model`) and its start x0_hat for this
  /// run: what the center and every station begin from, so that they begin from the same bits.
  template <typename Model>
  Model motion_model() const {
    return make_motion_model<Model>(scenario);
  }
  template <typename Model>
  GaussianState<Model::kDim> initial_estimate() const {
    return skyfuse::initial_estimate<Model>(scenario, true_initial_state(), mc_run);
  }
};

struct RunOverrides {
  std::optional<int> stations;      ///< default: every station of the scenario
  std::optional<int> steps;         ///< default: the scenario's
  std::optional<double> speed_kmh;  ///< default: the first speed the scenario lists
  std::uint64_t mc_run = 0;
  std::optional<ExchangeConfig::Kind> exchange;  ///< default: the scenario's network.exchange
  std::optional<int> fanout;                     ///< default: the scenario's network.fanout
  /// A scenario with generated traffic: how many aircraft (default: the generator's).
  std::optional<int> aircraft;
  /// A scenario with many aircraft: the tracker's associator (default: the scenario's).
  std::optional<std::string> associator;
};

/// The overrides of a run of `stations` stations for `steps` steps; everything else the
/// scenario's.
inline RunOverrides stations_and_steps(int stations, int steps) {
  RunOverrides overrides;
  overrides.stations = stations;
  overrides.steps = steps;
  return overrides;
}

/// Applies the overrides; throws std::invalid_argument naming the option and the value.
RunPlan make_run_plan(Scenario scenario, const RunOverrides& overrides);

/// The overrides every kind of run takes: `--steps` into `scenario`, and how many of its
/// stations take part (`--stations`, default all). Throws std::invalid_argument naming the
/// option and the value.
int apply_stations_and_steps(Scenario& scenario, const RunOverrides& overrides);

}  // namespace skyfuse
