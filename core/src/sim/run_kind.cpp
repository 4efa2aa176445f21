#include "skyfuse/sim/run_kind.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace skyfuse {

void require_one_aircraft(const Scenario& scenario, std::string_view what) {
  if (run_of(scenario) == RunOf::kOneAircraft) return;
  throw std::invalid_argument(
      fmt::format("scenario '{}' has many aircraft ('traffic'): `skyfuse sweep` runs it "
                  "in-process; {} keep one aircraft so far",
                  scenario.name, what));
}

void refuse_associator_for_one_aircraft(const Scenario& scenario, std::string_view option) {
  throw std::invalid_argument(fmt::format(
      "{}: scenario '{}' has one aircraft, known before the run: there is nothing to associate",
      option, scenario.name));
}

}  // namespace skyfuse
