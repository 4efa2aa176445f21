#pragma once
/// \file
/// How good a picture of many aircraft is, step by step and over a run, in the figures a
/// tracking engineer reads:
///  - GOSPA (metrics/gospa.hpp) between the aircraft present and the confirmed tracks, with its
///    localisation, missed and false parts;
///  - SIAP (single integrated air picture) figures, from each confirmed track's association to
///    the nearest aircraft within the GOSPA cut-off: completeness (share of aircraft with a
///    track), ambiguity (tracks per tracked aircraft, 1 at best), spuriousness (share of
///    tracks with no aircraft) and track-number changes (an aircraft's track id changing);
///  - the time from an aircraft's first detection to its first confirmed track.
/// Completeness counts an aircraft only where at least one station could see it and only from
/// its first confirmed track on: before that it is the time to confirm that speaks. GOSPA is
/// given twice: over every aircraft, and over what the network can see — the aircraft in at least
/// one station's view against the tracks less those on an aircraft out of view (a track coasting
/// on after its aircraft left every station's view is neither false nor asked for). On recorded
/// traffic, where most aircraft fly outside the stations' coverage, the second is the one that
/// says how well the network tracks.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/metrics/gospa.hpp"

namespace skyfuse {

/// An aircraft at a step: its index in the run's truth and where it is.
struct TruthPoint {
  std::size_t target = 0;
  Vector3 position = Vector3::Zero();
  bool in_view = false;  ///< within at least one station's field of view
  /// It reports an address to cooperative sensors (picture/identity.hpp).
  bool addressed = false;
};

/// A confirmed track at a step.
struct TrackPoint {
  std::uint64_t id = 0;
  Vector3 position = Vector3::Zero();
};

/// One step's figures.
struct PictureStep {
  int step = 0;
  std::size_t aircraft = 0;  ///< present
  std::size_t tracks = 0;    ///< confirmed
  Gospa gospa;               ///< over every aircraft present
  Gospa gospa_in_view;       ///< over the aircraft in view, without the tracks of those out of it
  /// Over the aircraft with an address in view, without the tracks of the others: what a
  /// network of cooperative sensors alone can see.
  Gospa gospa_addressed_in_view;
  std::size_t tracked = 0;   ///< aircraft with at least one track
  std::size_t spurious = 0;  ///< tracks with no aircraft within the cut-off
};

/// GOSPA and its parts, mean per step.
struct GospaMeans {
  double distance = 0.0;
  double localisation = 0.0;  ///< in GOSPA's units (m^p)
  double missed = 0.0;
  double false_tracks = 0.0;
};

struct PictureSummary {
  /// Over the aircraft in at least one station's view (PictureStep::gospa_in_view).
  GospaMeans in_view;
  /// Over the aircraft with an address in view (PictureStep::gospa_addressed_in_view).
  GospaMeans addressed_in_view;
  double gospa_mean = 0.0;
  double localisation_mean = 0.0;  ///< per step, in GOSPA's units (m^p)
  double missed_mean = 0.0;
  double false_mean = 0.0;
  /// The localisation error per assigned pair over the run, (sum of d^p / pairs)^(1/p): with
  /// p = 2 the RMS position error of the tracks GOSPA assigned, m.
  double localisation_per_pair_m = 0.0;
  double completeness = 0.0;
  double ambiguity = 0.0;
  /// Confirmed tracks on an aircraft beyond its own, summed over the steps (a duplicate track of
  /// one aircraft for 10 steps counts 10): a track within the cut-off of an aircraft that
  /// GOSPA's optimal assignment leaves over, counted on its nearest aircraft. Unlike
  /// ambiguity's excess (nearest aircraft only), two aircraft passing close with a track each
  /// count none.
  std::size_t duplicate_track_steps = 0;
  /// The same, of the aircraft with an address: a primary radar's track and the aircraft's own
  /// broadcast that should have been one (identity.hpp).
  std::size_t duplicate_track_steps_addressed = 0;
  double spuriousness = 0.0;
  std::size_t track_number_changes = 0;
  std::size_t aircraft_detected = 0;    ///< detected at least once
  std::size_t aircraft_confirmed = 0;   ///< of those, given a confirmed track
  double mean_time_to_confirm_s = 0.0;  ///< over the confirmed ones
};

class PictureScore {
 public:
  /// `targets`: how many aircraft the run's truth has.
  PictureScore(const GospaParameters& gospa, std::size_t targets, double time_step_s);

  /// Aircraft `target` was detected by some station at `step` (the first call per aircraft
  /// counts).
  void detected(std::size_t target, int step);
  /// Scores one step.
  const PictureStep& add_step(int step, std::span<const TruthPoint> aircraft,
                              std::span<const TrackPoint> tracks);

  const std::vector<PictureStep>& steps() const { return steps_; }
  PictureSummary summary() const;
  /// The aircraft each track was associated with in the last step (the track's index in the
  /// last add_step's `tracks`), for NEES; none for a spurious one.
  const std::vector<std::optional<std::size_t>>& last_association() const { return track_target_; }

 private:
  /// GOSPA over the aircraft `counted` keeps, against every track but those on an aircraft it
  /// leaves out; `whole` where it keeps them all.
  template <typename Counted>
  Gospa gospa_over(const Counted& counted, std::span<const TruthPoint> aircraft,
                   std::span<const TrackPoint> tracks,
                   std::span<const std::optional<std::size_t>> track_aircraft,
                   const Gospa& whole) const;

  GospaParameters gospa_;
  double time_step_s_;
  std::vector<PictureStep> steps_;
  std::vector<std::optional<int>> first_detected_;
  std::vector<std::optional<int>> first_confirmed_;
  std::vector<std::optional<std::uint64_t>> last_track_id_;
  std::size_t counted_ = 0;               // aircraft-steps counted for completeness
  std::size_t counted_tracked_ = 0;       // of those, tracked
  std::size_t tracked_total_ = 0;         // aircraft-steps tracked (all in view)
  std::size_t associated_total_ = 0;      // tracks associated, summed over steps
  std::size_t duplicates_ = 0;            // tracks left over near an aircraft, summed
  std::size_t duplicates_addressed_ = 0;  // of those, on addressed aircraft
  std::size_t tracks_total_ = 0;
  std::size_t spurious_total_ = 0;
  std::size_t number_changes_ = 0;
  std::vector<std::optional<std::size_t>> track_target_;
};

}  // namespace skyfuse
