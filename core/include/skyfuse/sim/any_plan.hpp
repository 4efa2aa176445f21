#pragma once
/// \file
/// A run's plan of either kind. Whether a run follows one aircraft (RunPlan) or many
/// (PicturePlan) is decided here, once, by its scenario's kind (run_kind.hpp). Every entry
/// point that runs a plan — `skyfuse run`, a station process, the center process — visits it
/// rather than asking the scenario again.

#include <utility>
#include <variant>

#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/sim/run_kind.hpp"
#include "skyfuse/sim/run_plan.hpp"

namespace skyfuse {

using AnyPlan = std::variant<RunPlan, PicturePlan>;

/// The plan of `scenario` with `overrides`, of the kind the scenario is; throws
/// std::invalid_argument for an override that kind does not take.
inline AnyPlan make_plan(Scenario scenario, const RunOverrides& overrides) {
  if (run_of(scenario) == RunOf::kManyAircraft) {
    return make_picture_plan(std::move(scenario), overrides);
  }
  return make_run_plan(std::move(scenario), overrides);
}

/// How many stations take part in `plan`.
inline int stations_of(const AnyPlan& plan) {
  return std::visit([](const CommonPlan& p) { return p.stations; }, plan);
}

}  // namespace skyfuse
