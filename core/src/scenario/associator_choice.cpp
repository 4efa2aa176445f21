#include "skyfuse/scenario/associator_choice.hpp"

#include <fmt/format.h>

#include <memory>
#include <stdexcept>

#include "skyfuse/picture/associator.hpp"
#include "skyfuse/picture/detection_prior.hpp"
#include "skyfuse/registry/filter_info.hpp"
#include "skyfuse/scenario/traffic_config.hpp"

namespace skyfuse {

void check_associator(const Scenario& scenario) {
  const AssociationConfig& association = scenario.tracker.association;
  const Associator* associator = find_associator(association.associator);
  if (associator == nullptr) {
    throw std::invalid_argument(fmt::format("unknown associator '{}'; known: {}",
                                            association.associator, associator_names()));
  }
  const FilterInfo filter = *find_filter(scenario.filter);
  if (associator->weighs_pairs && !filter.sums_weighed_pairs) {
    throw std::invalid_argument(fmt::format(
        "filter '{}' cannot fuse the weighed pairs of associator '{}' (its contributions do not "
        "add up); use a filter with an increment rule (ekf, ukf) or associator 'gnn'",
        filter.kind, associator->name));
  }
  // A weighing associator's center weighs a detection by its noise (R / w), which would move
  // the detection's linearisation point away from the peers' (docs/picture.md, "Relinearised
  // increments").
  if (associator->weighs_pairs && scenario.tracker.updater.relinearisations > 0) {
    throw std::invalid_argument(fmt::format(
        "associator '{}' does not yet take an updater that relinearises (its center weighs a "
        "detection by its noise, which moves the point it is linearised at away from the "
        "peers'); use associator 'gnn' or updater.relinearisations 0",
        associator->name));
  }
  for (const StationConfig& station : scenario.stations) {
    try {
      (void)detection_prior(station.detection.value(), station.sensor.kind, association);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("station {}: {}", station.id, e.what()));
    }
  }
}

void set_associator(Scenario& scenario, const std::string& name, const char* option) {
  Scenario changed = scenario;
  changed.tracker.association.associator = name;
  try {
    check_associator(changed);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format("{}: {}", option, e.what()));
  }
  scenario = std::move(changed);
}

}  // namespace skyfuse
