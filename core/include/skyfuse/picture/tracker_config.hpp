#pragma once
/// \file
/// The picture's tracker's settings, as a scenario's `tracker:` gives them (plain data; the
/// rules that use them are in hypothesiser.hpp, associator.hpp, initiation.hpp and
/// track_management.hpp).

#include <cstddef>
#include <optional>
#include <string>

namespace skyfuse {

struct AssociationConfig {
  /// The data associator, as the registry names it (picture/associator.hpp).
  std::string associator = "gnn";
  double gate_probability = 0.9999;  ///< of the chi-square(M) gate on a pair's NIS
  /// The most detections of one scan the assignment takes; the rest (a clutter burst) are
  /// counted and left out, so that a round's work stays bounded.
  std::size_t max_detections_per_scan = 4096;
  /// JPDA: a cluster of competing pairs whose joint events could number more than this is
  /// decided by GNN instead (and counted), so that a round's work stays bounded.
  std::size_t jpda_max_events = 100000;
  /// JPDA: false alarms per unit of measurement volume, every station's; none: each station's
  /// from its detection settings (picture/detection_prior.hpp).
  std::optional<double> clutter_density;
};

/// Identity (picture/identity.hpp).
struct IdentityConfig {
  /// Of the chi-square(M) sanity gate an addressed detection must pass against the track of
  /// its address, or be refused as a possible spoof: far wider than the association's gate,
  /// so that only a report that cannot be the track's aircraft fails it.
  double sanity_gate_probability = 1.0 - 1e-6;
  /// Of the chi-square(6) test on two confirmed tracks' positions and velocities by which a
  /// track without an address that holds the same aircraft as one with an address is dropped
  /// (picture/track_merge.hpp); 0: never.
  double merge_probability = 0.99;
};

struct InitiationConfig {
  double gate_probability = 0.999;  ///< of the chi-square(3) test that joins two detections
  int min_stations = 2;             ///< detections of this many stations start a track
  /// The initial velocity's standard deviation per axis: wide enough for any aircraft the
  /// scenario flies, m/s.
  double velocity_std_mps = 100.0;
};

struct ManagementConfig {
  int confirm_hits = 2;    ///< M
  int confirm_window = 3;  ///< N, at most 32
  int delete_misses = 5;   ///< K
  /// A track whose position standard deviation (sqrt of the trace of its position block)
  /// grows past this is deleted, m.
  double max_position_std_m = 1000.0;
};

/// The updater: how a station's detection updates a track (fusion/relinearised_increment.hpp).
struct UpdaterConfig {
  /// The most relinearisations a scenario may ask for: each is one more small solve per pair,
  /// and a second already gave the figures of one (docs/picture.md, "Relinearised increments").
  static constexpr int kMaxRelinearisations = 5;
  /// The EKF's: how many iterated steps take each detection's linearisation point from the
  /// track's prior towards where the detection puts it; 0, the default, linearises at the prior.
  int relinearisations = 0;
};

/// Registration (picture/registration.hpp): each station's biases estimated online from its
/// detections of confirmed tracks, and its detections corrected by them; none by default.
struct RegistrationConfig {
  /// A registration's name in the registry (find_registration).
  std::string kind = "none";
  /// The biases' prior standard deviations, each > 0.
  double range_std_m = 500.0;
  double azimuth_std_rad = 0.01;
  double elevation_std_rad = 0.01;
  double time_std_s = 1.0;
};

struct TrackerConfig {
  AssociationConfig association;
  RegistrationConfig registration;
  IdentityConfig identity;
  InitiationConfig initiation;
  ManagementConfig management;
  UpdaterConfig updater;
};

}  // namespace skyfuse
