#include "skyfuse/metrics/picture_score.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace skyfuse {

PictureScore::PictureScore(const GospaParameters& gospa, std::size_t targets, double time_step_s)
    : gospa_(gospa),
      time_step_s_(time_step_s),
      first_detected_(targets),
      first_confirmed_(targets),
      last_track_id_(targets) {}

void PictureScore::detected(std::size_t target, int step) {
  if (!first_detected_[target]) first_detected_[target] = step;
}

template <typename Counted>
Gospa PictureScore::gospa_over(const Counted& counted, std::span<const TruthPoint> aircraft,
                               std::span<const TrackPoint> tracks,
                               std::span<const std::optional<std::size_t>> track_aircraft,
                               const Gospa& whole) const {
  // Where every aircraft counts (the generated scenarios) that is the whole step, whose GOSPA
  // (an assignment, cubic in the aircraft) is not solved twice.
  if (std::ranges::all_of(aircraft, counted)) return whole;
  std::vector<Vector3> truths;
  std::vector<Vector3> estimates;
  for (const TruthPoint& a : aircraft) {
    if (counted(a)) truths.push_back(a.position);
  }
  // A track on an aircraft left out (one coasting after its aircraft left every station's view)
  // is neither false nor asked for; a track on no aircraft is false.
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    if (!track_aircraft[t] || counted(aircraft[*track_aircraft[t]])) {
      estimates.push_back(tracks[t].position);
    }
  }
  return gospa(truths, estimates, gospa_);
}

const PictureStep& PictureScore::add_step(int step, std::span<const TruthPoint> aircraft,
                                          std::span<const TrackPoint> tracks) {
  PictureStep row;
  row.step = step;
  row.aircraft = aircraft.size();
  row.tracks = tracks.size();
  std::vector<Vector3> truths;
  std::vector<Vector3> estimates;
  for (const TruthPoint& a : aircraft) truths.push_back(a.position);
  for (const TrackPoint& t : tracks) estimates.push_back(t.position);
  std::vector<int> assigned_track;  // per aircraft: its track in GOSPA's assignment, or -1
  row.gospa = gospa(truths, estimates, gospa_, &assigned_track);

  // Each track to its nearest aircraft within the cut-off.
  track_target_.assign(tracks.size(), std::nullopt);
  std::vector<std::optional<std::size_t>> track_aircraft(tracks.size());  // index into `aircraft`
  std::vector<std::size_t> tracks_of(aircraft.size(), 0);
  std::vector<std::optional<std::size_t>> nearest_track(aircraft.size());
  std::vector<double> nearest_distance(aircraft.size(), std::numeric_limits<double>::infinity());
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    double best = gospa_.cutoff_m;
    std::optional<std::size_t> best_aircraft;
    for (std::size_t a = 0; a < aircraft.size(); ++a) {
      const double d = (aircraft[a].position - tracks[t].position).norm();
      if (d < best) {
        best = d;
        best_aircraft = a;
      }
    }
    if (!best_aircraft) {
      ++row.spurious;
      continue;
    }
    track_target_[t] = aircraft[*best_aircraft].target;
    track_aircraft[t] = best_aircraft;
    ++tracks_of[*best_aircraft];
    if (best < nearest_distance[*best_aircraft]) {
      nearest_distance[*best_aircraft] = best;
      nearest_track[*best_aircraft] = t;
    }
  }
  // What the network can see: the aircraft in view, and every track but those on an aircraft
  // out of view. And the like of it over the aircraft with an address in view: what a network of
  // cooperative sensors alone sees, so that a mixed network's picture of those same aircraft
  // can be set beside it.
  row.gospa_in_view = gospa_over([](const TruthPoint& a) { return a.in_view; }, aircraft, tracks,
                                 track_aircraft, row.gospa);
  row.gospa_addressed_in_view =
      gospa_over([](const TruthPoint& a) { return a.in_view && a.addressed; }, aircraft, tracks,
                 track_aircraft, row.gospa);

  // A duplicate: a track within the cut-off of an aircraft that GOSPA's optimal assignment
  // leaves over. Every aircraft within its cut-off then has a track of its own (else pairing
  // them would lower GOSPA), so it is a second track, counted on its nearest aircraft; two
  // aircraft passing close with a track each are none, though both tracks be nearest one.
  std::vector<bool> in_assignment(tracks.size(), false);
  for (const int t : assigned_track) {
    if (t >= 0) in_assignment[static_cast<std::size_t>(t)] = true;
  }
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    if (!track_aircraft[t] || in_assignment[t]) continue;
    ++duplicates_;
    if (aircraft[*track_aircraft[t]].addressed) ++duplicates_addressed_;
  }

  for (std::size_t a = 0; a < aircraft.size(); ++a) {
    const std::size_t target = aircraft[a].target;
    const bool tracked = tracks_of[a] > 0;
    if (tracked) {
      ++row.tracked;
      associated_total_ += tracks_of[a];
      if (!first_confirmed_[target]) first_confirmed_[target] = step;
      const std::uint64_t id = tracks[*nearest_track[a]].id;
      if (last_track_id_[target] && *last_track_id_[target] != id) ++number_changes_;
      last_track_id_[target] = id;
    }
    if (aircraft[a].in_view && first_confirmed_[target]) {
      ++counted_;
      if (tracked) ++counted_tracked_;
    }
  }
  tracked_total_ += row.tracked;
  tracks_total_ += row.tracks;
  spurious_total_ += row.spurious;
  steps_.push_back(row);
  return steps_.back();
}

namespace {

// The mean over `steps` of one of each step's GOSPAs (`which`: over every aircraft, or in view).
GospaMeans mean_of(std::span<const PictureStep> steps, Gospa PictureStep::*which) {
  GospaMeans m;
  for (const PictureStep& row : steps) {
    const Gospa& g = row.*which;
    m.distance += g.distance;
    m.localisation += g.localisation;
    m.missed += g.missed;
    m.false_tracks += g.false_tracks;
  }
  const auto n = static_cast<double>(steps.size());
  m.distance /= n;
  m.localisation /= n;
  m.missed /= n;
  m.false_tracks /= n;
  return m;
}

}  // namespace

PictureSummary PictureScore::summary() const {
  PictureSummary s;
  if (!steps_.empty()) {
    double localisation = 0.0;
    std::size_t pairs = 0;
    for (const PictureStep& row : steps_) {
      localisation += row.gospa.localisation;
      pairs += row.gospa.assigned;
    }
    const GospaMeans all = mean_of(steps_, &PictureStep::gospa);
    s.gospa_mean = all.distance;
    s.localisation_mean = all.localisation;
    s.missed_mean = all.missed;
    s.false_mean = all.false_tracks;
    s.in_view = mean_of(steps_, &PictureStep::gospa_in_view);
    s.addressed_in_view = mean_of(steps_, &PictureStep::gospa_addressed_in_view);
    if (pairs > 0) {
      s.localisation_per_pair_m =
          std::pow(localisation / static_cast<double>(pairs), 1.0 / gospa_.order);
    }
  }
  const auto share = [](std::size_t part, std::size_t whole) {
    return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
  };
  s.completeness = share(counted_tracked_, counted_);
  s.ambiguity = share(associated_total_, tracked_total_);
  s.duplicate_track_steps = duplicates_;
  s.duplicate_track_steps_addressed = duplicates_addressed_;
  s.spuriousness = share(spurious_total_, tracks_total_);
  s.track_number_changes = number_changes_;
  double confirm_steps = 0.0;
  for (std::size_t t = 0; t < first_detected_.size(); ++t) {
    if (!first_detected_[t]) continue;
    ++s.aircraft_detected;
    if (!first_confirmed_[t]) continue;
    ++s.aircraft_confirmed;
    confirm_steps += std::max(0, *first_confirmed_[t] - *first_detected_[t]);
  }
  if (s.aircraft_confirmed > 0) {
    s.mean_time_to_confirm_s =
        confirm_steps * time_step_s_ / static_cast<double>(s.aircraft_confirmed);
  }
  return s;
}

}  // namespace skyfuse
