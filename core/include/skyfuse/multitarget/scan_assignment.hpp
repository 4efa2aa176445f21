#pragma once
/// \file
/// One station's global-nearest-neighbour assignment of its own detections to the common
/// predicted tracks: at most one detection per track and one track per detection, at least
/// total cost, costs only from the track's prior and the station's own sensor. Because no
/// station's assignment constrains another's, the union of the stations' assignments is the
/// joint one, which is what keeps the network's picture the center's.
///
/// The cost of a pair is its normalised innovation squared d^2 = nu^T S^-1 nu, S = H P H^T + R;
/// a pair enters only within the chi-square gate g, and a track may stay unassigned at cost g.
/// A coarse pre-gate on positions (detections sorted by east coordinate; a track looks only at
/// those within a radius of its own) keeps the work near linear in tracks and detections; the
/// radius, sqrt(g) times the sum of the two position standard deviations, bounds the exact
/// gate for sensors that are linear in the position and nearly so for the others.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "skyfuse/association/assignment.hpp"
#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/multitarget/initiation.hpp"
#include "skyfuse/multitarget/scan.hpp"
#include "skyfuse/multitarget/track.hpp"

namespace skyfuse {

/// The position spread of a detection whose fix is degenerate: the pre-gate then compares it
/// with every track.
inline constexpr double kDegenerateFixStdM = 1e12;

/// What one station's assignment decided.
struct ScanAssignment {
  std::vector<int> detection_of_track;      ///< per track (picture order): a detection, or -1
  std::vector<std::uint32_t> unassociated;  ///< detections no track took, ascending
  std::size_t dropped = 0;                  ///< detections beyond max_detections_per_scan
  std::size_t gated_pairs = 0;
  std::size_t largest_cluster = 0;
};

/// Reusable buffers of assign_scan: a round allocates only when the picture grows.
struct AssignmentWork {
  struct Candidate {
    double east;
    double std_m;
    Vector3 position;
    std::uint32_t index;
  };
  std::vector<Candidate> candidates;
  std::vector<association::GatedPair> pairs;
  std::vector<double> unassigned_cost;
};

/// Assigns `scan` (the station's detections; `sensor` its sensor, of the tracks' state
/// dimension N) to the tracks' `priors` with the gate threshold `gate` (chi-square(M)
/// quantile).
template <typename Sensor, int N>
ScanAssignment assign_scan(std::span<const GaussianState<N>> priors, const Sensor& sensor,
                           const Scan<Sensor::kMeasDim>& scan, double gate,
                           std::size_t max_detections, AssignmentWork& work) {
  constexpr int M = Sensor::kMeasDim;
  ScanAssignment result;
  const std::size_t taken = std::min(scan.detections.size(), max_detections);
  result.dropped = scan.detections.size() - taken;

  // The detections' positions, by east coordinate, and how uncertain each is.
  work.candidates.clear();
  double widest = 0.0;
  for (std::uint32_t j = 0; j < taken; ++j) {
    const auto fix = fix_position(scan.station_id, j, sensor, scan.detections[j], scan.noise);
    // A detection whose fix is degenerate is compared with every track.
    const Vector3 position = fix ? fix->position : sensor.position_of(scan.detections[j]);
    const double std_m = fix ? std::sqrt(fix->covariance.trace()) : kDegenerateFixStdM;
    widest = std::max(widest, std_m);
    work.candidates.push_back({position.x(), std_m, position, j});
  }
  std::sort(work.candidates.begin(), work.candidates.end(), [](const auto& a, const auto& b) {
    return a.east < b.east || (a.east == b.east && a.index < b.index);
  });

  const double reach = std::sqrt(gate);
  work.pairs.clear();
  for (std::size_t t = 0; t < priors.size(); ++t) {
    const GaussianState<N>& prior = priors[t];
    const Vector3 p = prior.mean.template head<3>();
    const double track_std = std::sqrt(prior.covariance.template topLeftCorner<3, 3>().trace());
    const double radius = reach * (track_std + widest);
    const Matrix<M, N> h = sensor.jacobian(prior.mean);
    const Vector<M> predicted = sensor.predict(prior.mean);
    Covariance<M> s = h * prior.covariance * h.transpose() + scan.noise;
    symmetrize(s);
    SmallCholesky<M> s_factor;
    if (!s_factor.compute(s)) continue;  // a track with no usable S takes nothing this round
    auto from = std::lower_bound(work.candidates.begin(), work.candidates.end(), p.x() - radius,
                                 [](const auto& c, double east) { return c.east < east; });
    for (auto c = from; c != work.candidates.end() && c->east <= p.x() + radius; ++c) {
      if ((c->position - p).norm() > reach * (track_std + c->std_m)) continue;
      const Vector<M> nu = sensor.residual(scan.detections[c->index], predicted);
      const double nis = nu.dot(s_factor.solve(nu));
      if (nis <= gate) {
        work.pairs.push_back({static_cast<int>(t), static_cast<int>(c->index), nis});
      }
    }
  }
  result.gated_pairs = work.pairs.size();
  work.unassigned_cost.assign(priors.size(), gate);
  const association::GatedAssignment solved =
      association::solve_gated_assignment(priors.size(), taken, work.pairs, work.unassigned_cost);
  result.detection_of_track = solved.column_of_row;
  result.largest_cluster = solved.largest_cluster;
  std::vector<char> associated(taken, 0);
  for (const int j : result.detection_of_track) {
    if (j >= 0) associated[static_cast<std::size_t>(j)] = 1;
  }
  for (std::uint32_t j = 0; j < taken; ++j) {
    if (!associated[j]) result.unassociated.push_back(j);
  }
  return result;
}

}  // namespace skyfuse
