#pragma once
/// \file
/// What one run of a scenario with many aircraft is, for every process that takes part: the
/// scenario after the command-line overrides, which stations take part (the first M) and which
/// Monte-Carlo run index selects the noise. Stations and harness build the same plan from the
/// same options, so they simulate the same run; the in-process picture run (sim/picture_run.hpp)
/// is its twin.

#include <cstdint>
#include <span>
#include <vector>

#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/sim/run_plan.hpp"

namespace skyfuse {

/// Many aircraft's plan: each aircraft flies its own path and speeds (the scenario's traffic),
/// so it holds nothing beside what every plan holds.
struct PicturePlan : CommonPlan {};

/// Applies the overrides to `scenario` (a run of many aircraft, run_kind.hpp); throws
/// std::invalid_argument naming an option a run of many aircraft does not take (a speed: each
/// aircraft flies its own) or a value out of range. The exchange is flat unless the scenario or
/// `--exchange` asks for the tree.
PicturePlan make_picture_plan(Scenario scenario, const RunOverrides& overrides);

}  // namespace skyfuse
