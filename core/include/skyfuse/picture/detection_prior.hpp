#pragma once
/// \file
/// A station's DetectionPrior (scan_association.hpp) from its detection settings: what JPDA
/// needs to know of its sensor as a sensor, resolved once per station.

#include <optional>
#include <string_view>

#include "skyfuse/picture/scan_association.hpp"
#include "skyfuse/picture/tracker_config.hpp"
#include "skyfuse/traffic/detection_model.hpp"

namespace skyfuse {

/// The density with which a scan leaves nothing gated (no clutter asked for): new aircraft only,
/// per unit of measurement volume, small enough never to outweigh a detection within the gate.
inline constexpr double kNoClutterDensity = 1e-12;

/// False alarms per unit of measurement volume of a station whose sensor is of kind
/// `sensor_kind` with detection settings `detection`: the clutter's mean over the volume of the
/// field of view in measurement space, where the clutter is uniform there (a range, azimuth and
/// elevation radar's); kNoClutterDensity without clutter; none where it is not uniform (the
/// scenario must then give it).
std::optional<double> clutter_density_of(const DetectionConfig& detection,
                                         std::string_view sensor_kind);

/// The station's prior: its P_D, the gate's P_G and its false-alarm density (the scenario's
/// `tracker: {clutter_density}` where given). std::invalid_argument where none can be had.
DetectionPrior detection_prior(const DetectionConfig& detection, std::string_view sensor_kind,
                               const AssociationConfig& association);

}  // namespace skyfuse
