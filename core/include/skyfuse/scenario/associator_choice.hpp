#pragma once
/// \file
/// Whether a scenario with many aircraft can run the associator its tracker names: the filter
/// part must fuse what the associator gives (weighed pairs need an increment rule) and every
/// station's detection prior must be known (JPDA's false-alarm density). The loader checks it;
/// `--associator` of `skyfuse sweep` and `skyfuse run` swaps the associator and checks again.

#include <string>

#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

/// Throws std::invalid_argument saying why `scenario` (with traffic) cannot run its associator.
void check_associator(const Scenario& scenario);

/// `scenario`'s tracker (a scenario with traffic: the plan makers call it for many aircraft
/// only) with associator `name`, checked (std::invalid_argument, naming the option `option`,
/// where it cannot run). The traffic config is shared: it is copied first.
void set_associator(Scenario& scenario, const std::string& name, const char* option);

}  // namespace skyfuse
