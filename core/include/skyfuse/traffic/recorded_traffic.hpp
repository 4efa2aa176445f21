#pragma once
/// \file
/// Real traffic as truth: the aircraft of an OpenSky state-vector CSV file, placed in a
/// scenario's east-north-up frame and resampled to the run's steps, so that sensors and metrics
/// can be run against flown trajectories instead of generated ones.
///
/// The file has a header line naming its columns, in any order; these are required: time,
/// icao24, lat, lon, velocity, heading, vertrate, onground, geoaltitude, baroaltitude,
/// lastposupdate (others, such as callsign or squawk, are ignored). Times are Unix seconds,
/// angles degrees (heading clockwise from true north), speeds m/s, altitudes metres, and any
/// field but time and icao24 may be empty. Rows are in time order, as OpenSky writes them.
///
/// A usable row is placed at its `lastposupdate`, the time its position was received, not at
/// `time`, when the state was written: a position up to max_staleness_s old would otherwise be
/// misplaced by that age times the speed. A row repeating a position already sampled (the same
/// `lastposupdate`) adds nothing.
///
/// Between usable samples the position follows a cubic Hermite spline through the samples'
/// positions and velocities, so position and velocity are continuous and the acceleration is
/// the spline's second derivative. Altitudes are taken as heights above the WGS-84 ellipsoid,
/// as the anchor's; the barometric one is a pressure altitude and off by tens of metres.
///
/// The rows are also what the aircraft broadcast (ADS-B): each target keeps, per step, the
/// newest report with a velocity sent since the step before, carried forward to the step's time
/// (TargetTruth::broadcasts), for a receiver that replays them (DetectionConfig::
/// replays_broadcasts). Steps without such a report are the recording's own gaps. The truth is
/// made from the same reports, so a report differs from it only by the carrying forward.

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <vector>

#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/traffic/target_truth.hpp"

namespace skyfuse {

struct RecordedTrafficOptions {
  /// Unix time (s) of step 0; NaN takes the file's first `time`.
  double start_time_s = std::numeric_limits<double>::quiet_NaN();
  double time_step_s = 1.0;
  /// Steps 0..steps (steps + 1 instants), as a scenario's truth has.
  int steps = 0;
  /// A row whose position is older than this (time - lastposupdate, s) is skipped.
  double max_staleness_s = 15.0;
  /// The GNSS (geometric) altitude first, the barometric one where it is empty; false: the
  /// other way round.
  bool use_geometric_altitude = true;
};

/// The longest time (s) between consecutive usable samples of one aircraft that the spline
/// bridges; a longer gap ends one presence and starts another.
inline constexpr double kMaxRecordedSampleGapS = 30.0;

struct RecordedTraffic {
  /// One entry per presence of an aircraft in the run, sorted by label: its icao24 for its
  /// first presence in the file, icao24 + "#n" for its n-th after gaps. Every presence counts
  /// towards n, kept or not, so a label names the same flight whatever the run's window.
  std::vector<TargetTruth> targets;
  /// Data rows read (the header and blank lines not counted).
  std::size_t rows = 0;
  /// Rows skipped, each counted once, tested in this order: on the ground; without latitude,
  /// longitude or altitude; with a position older than max_staleness_s (or of unknown age).
  std::size_t rows_on_ground = 0;
  std::size_t rows_without_position = 0;
  std::size_t stale_rows = 0;
  /// Usable rows whose position was already sampled (same or earlier lastposupdate).
  std::size_t repeated_position_rows = 0;
  /// Presences with a single usable sample, which give no trajectory and are dropped.
  std::size_t single_sample_aircraft = 0;
};

/// Reads `path` and resamples its aircraft at start_time_s + k * time_step_s, k = 0..steps,
/// in `anchor`'s east-north-up frame. An aircraft is present at the steps between its first
/// and last usable sample of a presence. Throws std::runtime_error "<path>:<line>: <what>" for
/// a file that cannot be read or is empty, a missing column, a field that is not a number, or
/// a time earlier than the previous row's; std::invalid_argument for options out of range.
RecordedTraffic read_opensky_states(const std::filesystem::path& path, const GeoAnchor& anchor,
                                    const RecordedTrafficOptions& options);

}  // namespace skyfuse
