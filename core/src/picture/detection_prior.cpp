#include "skyfuse/picture/detection_prior.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/associator.hpp"

namespace skyfuse {

std::optional<double> clutter_density_of(const DetectionConfig& detection,
                                         std::string_view sensor_kind) {
  if (detection.clutter_per_scan <= 0.0) return kNoClutterDensity;
  if (sensor_kind != RangeAzimuthElevation<6>::kKind) return std::nullopt;
  // FieldOfView::draw_point: range, azimuth and elevation each uniform over the field of view.
  const FieldOfView& fov = detection.field_of_view;
  const double azimuths = 2.0 * fov.azimuth_sector.value_or(AzimuthSector{}).half_width_rad;
  const double elevations = std::numbers::pi / 2.0 - fov.min_elevation_rad;
  const double volume = fov.max_range_m * azimuths * elevations;
  if (!(volume > 0.0) || !std::isfinite(volume)) return std::nullopt;
  return detection.clutter_per_scan / volume;
}

DetectionPrior detection_prior(const DetectionConfig& detection, std::string_view sensor_kind,
                               const AssociationConfig& association) {
  DetectionPrior prior;
  prior.detection_probability = detection.probability;
  prior.gate_probability = association.gate_probability;
  std::optional<double> density = association.clutter_density
                                      ? association.clutter_density
                                      : clutter_density_of(detection, sensor_kind);
  const Associator* associator = find_associator(association.associator);
  if (!density && (associator == nullptr || !associator->weighs_pairs)) {
    density = kNoClutterDensity;  // GNN weighs no pair: the density is never read
  }
  if (!density) {
    throw std::invalid_argument(
        fmt::format("tracker: a {} sensor's clutter is not uniform in its measurement space; give "
                    "tracker.clutter_density (false alarms per unit of measurement volume)",
                    sensor_kind));
  }
  prior.clutter_density = *density;
  return prior;
}

}  // namespace skyfuse
