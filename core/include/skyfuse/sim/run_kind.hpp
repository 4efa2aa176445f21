#pragma once
/// \file
/// A run's kind: one aircraft, known before the run (a RunPlan, a one-aircraft sweep), or many,
/// tracked as a picture (a PicturePlan, a picture sweep). It is the scenario's — many where it
/// has 'traffic' — and it is read here and nowhere else: the plan makers decide by it
/// (any_plan.hpp, sweep_plan.hpp), and what takes one kind only refuses the other through it.
/// What a run over DDS does for each kind is its policy, harness/run/run_over_dds.hpp's RunKind.

#include <string_view>

#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

/// Of how many aircraft a run is.
enum class RunOf { kOneAircraft, kManyAircraft };

/// The kind of run `scenario` makes.
inline RunOf run_of(const Scenario& scenario) {
  return scenario.has_many_targets() ? RunOf::kManyAircraft : RunOf::kOneAircraft;
}

/// Throws std::invalid_argument unless `scenario` makes a run of one aircraft; `what` (say,
/// "soak runs") names what keeps to one.
void require_one_aircraft(const Scenario& scenario, std::string_view what);

/// Throws std::invalid_argument saying that `option` (an associator's choice) means nothing for
/// `scenario`, a run of one aircraft, known before the run.
[[noreturn]] void refuse_associator_for_one_aircraft(const Scenario& scenario,
                                                     std::string_view option);

}  // namespace skyfuse
