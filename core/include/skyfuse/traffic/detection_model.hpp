#pragma once
/// \file
/// How a station's sensor behaves as a sensor: what it can see (its field of view), how often
/// it sees an aircraft there (the probability of detection) and what it reports that is not
/// there (clutter: a Poisson number of false alarms per scan, spread uniformly over range,
/// azimuth and elevation within the field of view). Angles as the range/azimuth/elevation
/// sensor measures them: azimuth counter-clockwise from east (x), elevation up from the
/// horizontal.

#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>

#include "skyfuse/core/types.hpp"
#include "skyfuse/random/counter_rng.hpp"
#include "skyfuse/traffic/sensor_bias.hpp"

namespace skyfuse {

/// A sector of azimuths: within half_width of centre, both in radians.
struct AzimuthSector {
  double centre_rad = 0.0;
  double half_width_rad = std::numbers::pi;
};

struct FieldOfView {
  double max_range_m = std::numeric_limits<double>::infinity();
  double min_elevation_rad = -std::numbers::pi / 2.0;
  std::optional<AzimuthSector> azimuth_sector;  ///< none: all round

  /// Whether a target at `position` is within the field of view of a sensor at `site`.
  bool contains(const Vector3& site, const Vector3& position) const;
  /// A point drawn uniformly in (range, azimuth, elevation) over the field of view, from a
  /// sensor at `site`; needs a finite max_range_m.
  Vector3 draw_point(const Vector3& site, CounterRng& rng) const;
};

struct DetectionConfig {
  double probability = 1.0;  ///< P_D of a target within the field of view
  FieldOfView field_of_view;
  double clutter_per_scan = 0.0;  ///< the Poisson mean of false alarms per scan
  /// A false alarm's velocity, for a sensor that measures one (position_velocity): each
  /// component uniform in [-this, this], m/s.
  double clutter_max_speed_mps = 100.0;
  /// A cooperative sensor (a Mode S radar, an ADS-B or Remote ID receiver): it hears only
  /// aircraft with an address, and reports each one's address with its detection.
  bool reports_address = false;
  /// A receiver of recorded broadcasts: its detections are the recorded aircraft's own reports
  /// (TargetTruth::broadcasts), not drawn from the truth; no noise is added, and an aircraft
  /// that sent nothing since the step before is not heard. P_D and clutter apply on top. Only
  /// a cooperative position_velocity sensor on recorded traffic (the loader checks).
  bool replays_broadcasts = false;
  /// The station's systematic errors (its own `bias:`), added to every detection of an
  /// aircraft; none by default. Not applied to a replayed broadcast (the loader refuses both).
  SensorBias bias;

  /// The largest clutter mean a scenario may ask for: beyond it a scan's work is no longer
  /// bounded by the aircraft.
  static constexpr double kMaxClutterPerScan = 1000.0;
};

/// A Poisson-distributed count with mean `mean` (>= 0), drawn from `rng`.
std::uint32_t draw_poisson(double mean, CounterRng& rng);

}  // namespace skyfuse
