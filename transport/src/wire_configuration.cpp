#include "skyfuse/transport/wire_configuration.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace skyfuse::transport {

void require_wire_configuration(const Scenario& scenario) {
  // Every registered sensor runs, mixed or not; the processes are compiled for one model.
  if (scenario.filter.motion_model.kind != WireModel::kKind) {
    throw std::invalid_argument(fmt::format(
        "scenario '{}': motion model {}: the station and center processes run {} only for now; "
        "other models run in-process",
        scenario.name, scenario.filter.motion_model.kind, WireModel::kKind));
  }
}

}  // namespace skyfuse::transport
