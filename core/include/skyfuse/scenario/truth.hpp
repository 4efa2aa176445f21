#pragma once
/// \file
/// The true trajectory of the target: straight flight at the initial velocity, changed by the
/// scenario's manoeuvres. Each step is integrated exactly (a turn is a circular arc), with
/// manoeuvre windows rounded to whole steps.

#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

/// Entries of the target's true kinematics [p; v; a], which every sensor measures whatever
/// state a filter keeps of it.
inline constexpr int kKinematicsDim = 9;

/// states[k] = [p; v; a] at time k * dt for k = 0..steps (steps + 1 entries); a is the
/// acceleration acting over the step that starts at k.
struct TruthTrajectory {
  std::vector<Vector<kKinematicsDim>> states;

  Vector3 position(std::size_t step) const { return states[step].head<3>(); }
};

TruthTrajectory generate_truth(const TargetConfig& target, double speed_mps, double time_step_s,
                               int steps);

}  // namespace skyfuse
