#pragma once
/// \file
/// The generalised optimal sub-pattern assignment metric (GOSPA; Rahmathullah, García-Fernández
/// and Svensson, 2017) with alpha = 2, between the true positions of the aircraft present and
/// the positions of the tracks: the distance of the best assignment, each pair's distance cut
/// off at c, every target left without a track and every track left without a target costing
/// c^p / 2. With alpha = 2 it splits into what a tracking engineer reads apart: localisation
/// error of the assigned pairs, missed targets, false tracks.

#include <cstddef>
#include <span>
#include <vector>

#include "skyfuse/core/types.hpp"

namespace skyfuse {

struct GospaParameters {
  double cutoff_m = 10.0;  ///< c > 0: a pair farther apart is a miss and a false track
  double order = 2.0;      ///< p >= 1
};

/// GOSPA and its parts. The parts are in units of distance^p and add up to distance^p.
struct Gospa {
  double distance = 0.0;      ///< (localisation + missed + false_tracks)^(1/p)
  double localisation = 0.0;  ///< sum over assigned pairs of d^p
  double missed = 0.0;        ///< c^p / 2 per target without a track
  double false_tracks = 0.0;  ///< c^p / 2 per track without a target
  std::size_t assigned = 0;
  std::size_t missed_targets = 0;
  std::size_t false_estimates = 0;
};

/// GOSPA between `truths` and `estimates` (positions, m); `assignment`, if given, receives per
/// truth the index of its estimate in the optimal assignment, or -1. Throws
/// std::invalid_argument for a cut-off <= 0 or an order < 1.
Gospa gospa(std::span<const Vector3> truths, std::span<const Vector3> estimates,
            const GospaParameters& parameters, std::vector<int>* assignment = nullptr);

}  // namespace skyfuse
