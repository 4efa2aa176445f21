#include "skyfuse/transport/wire_configuration.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace skyfuse::transport {

void require_wire_configuration(const Scenario& scenario, const options::NodeOptions& node) {
  // Every registered sensor runs, mixed or not; the processes are compiled for these models.
  const std::string& model = scenario.filter.motion_model.kind;
  const bool ncrkf = scenario.filter.kind == "ncrkf";
  if (scenario.filter.kind == "imm" && node.refusion_lag != 0) {
    throw std::invalid_argument(
        "--refusion-lag: filter imm fuses each round once for now; leave it at 0");
  }
  if (ncrkf && node.nis_gate().enabled()) {
    throw std::invalid_argument(fmt::format(
        "scenario '{}': filter ncrkf takes no NIS gate (its increments have no innovation)",
        scenario.name));
  }
  if (model == WireModel::kKind || (ncrkf && model == TdoaRelativeMotion::kKind)) return;
  throw std::invalid_argument(
      fmt::format("scenario '{}': motion model {}: the station and center processes run {} (and "
                  "{} with filter ncrkf) only for now; other models run in-process",
                  scenario.name, model, WireModel::kKind, TdoaRelativeMotion::kKind));
}

}  // namespace skyfuse::transport
