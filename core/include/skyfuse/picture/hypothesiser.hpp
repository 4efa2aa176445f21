#pragma once
/// \file
/// The hypothesiser: the part of the tracker that says which (track, detection) pairs of one
/// station's scan are possible and what each costs, before any associator decides. Costs come
/// only from the track's prior and the station's own sensor, so every peer computes the same
/// hypotheses from the same predicted picture and the same published scan.
///
/// A pair (t, j) is a hypothesis when its normalised innovation squared d^2 = nu^T S^-1 nu,
/// S = H P H^T + R, lies within the chi-square gate g; it carries d^2 (GNN's cost) and the log
/// of its Gaussian density N(nu; 0, S) (JPDA's likelihood). Every track also has the
/// missed-detection hypothesis, whose GNN cost is g (picture/associators/).
///
/// A coarse pre-gate on positions (detections sorted by east coordinate; a track looks only at
/// those within a radius of its own) keeps the work near linear in tracks and detections; the
/// radius, sqrt(g) times the sum of the two position standard deviations, bounds the exact
/// gate for sensors that are linear in the position and nearly so for the others.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/picture/address.hpp"
#include "skyfuse/picture/initiation.hpp"
#include "skyfuse/picture/scan.hpp"

namespace skyfuse {

/// The position spread of a detection whose fix is degenerate: the pre-gate then compares it
/// with every track.
inline constexpr double kDegenerateFixStdM = 1e12;

/// One gated pair: track `track` (its index in picture order) may have produced detection
/// `detection` (its index in the scan).
struct Hypothesis {
  int track = 0;
  int detection = 0;
  double nis = 0.0;          ///< d^2 = nu^T S^-1 nu
  double log_density = 0.0;  ///< log N(nu; 0, S), where asked for; else 0
};

/// Every gated pair of one station's scan against the predicted tracks, in the order the
/// pre-gate finds them (track by track; within a track, by the detections' east coordinate).
struct Hypotheses {
  std::size_t tracks = 0;
  std::size_t detections = 0;  ///< those taken: at most the bound on a scan
  std::size_t dropped = 0;     ///< detections beyond the bound, left out and counted
  double gate = 0.0;           ///< g: the chi-square quantile of the gate
  std::vector<Hypothesis> pairs;
};

/// Reusable buffers of the hypothesiser: a round allocates only when the picture grows.
struct HypothesiserWork {
  struct Candidate {
    double east;
    double std_m;
    Vector3 position;
    std::uint32_t index;
  };
  std::vector<Candidate> candidates;
};

/// The hypotheses of `scan` (the station's detections; `sensor` its sensor, of the tracks'
/// state dimension N) against the tracks' `priors`, within the gate `gate` (chi-square(M)
/// quantile), taking at most `max_detections` detections, each pair's log-density computed
/// only `with_densities` (an associator that reads them: GNN's costs need none), leaving out
/// the tracks, detections and pairs identity decided (`mask`, picture/identity.hpp).
/// Written into `out`, whose storage is kept from round to round.
template <typename Sensor, int N>
void hypothesise(std::span<const GaussianState<N>> priors, const Sensor& sensor, const Scan& scan,
                 double gate, std::size_t max_detections, bool with_densities,
                 const IdentityMask& mask, HypothesiserWork& work, Hypotheses& out) {
  constexpr int M = Sensor::kMeasDim;
  const Covariance<M> noise = fixed_noise<M>(scan.noise);
  const bool reports_own_noise = !scan.reported_std.empty();
  const std::size_t taken = std::min(scan.detections.size(), max_detections);
  out.tracks = priors.size();
  out.detections = taken;
  out.dropped = scan.detections.size() - taken;
  out.gate = gate;
  out.pairs.clear();

  // The detections' positions, by east coordinate, and how uncertain each is.
  work.candidates.clear();
  double widest = 0.0;
  for (std::uint32_t j = 0; j < taken; ++j) {
    if (mask.skips_detection(j)) continue;
    const Vector<M> z = fixed_detection<M>(scan.detections[j]);
    const auto fix = fix_position(scan.station_id, j, sensor, z,
                                  reported_noise<M>(noise, reported_std_at(scan.reported_std, j)));
    // A detection whose fix is degenerate is compared with every track.
    const Vector3 position = fix ? fix->position : sensor.position_of(z);
    const double std_m = fix ? std::sqrt(fix->covariance.trace()) : kDegenerateFixStdM;
    widest = std::max(widest, std_m);
    work.candidates.push_back({position.x(), std_m, position, j});
  }
  std::sort(work.candidates.begin(), work.candidates.end(), [](const auto& a, const auto& b) {
    return a.east < b.east || (a.east == b.east && a.index < b.index);
  });

  const double reach = std::sqrt(gate);
  const double log_2pi_m = M * std::log(2.0 * std::numbers::pi);
  for (std::size_t t = 0; t < priors.size(); ++t) {
    if (mask.skips_track(t)) continue;
    const bool track_holds_address = mask.holds_address(t);
    const GaussianState<N>& prior = priors[t];
    const Vector3 p = prior.mean.template head<3>();
    const double track_std = std::sqrt(prior.covariance.template topLeftCorner<3, 3>().trace());
    const double radius = reach * (track_std + widest);
    const Matrix<M, N> h = sensor.jacobian(prior.mean);
    const Vector<M> predicted = sensor.predict(prior.mean);
    const Covariance<M> projected = h * prior.covariance * h.transpose();
    Covariance<M> s = projected + noise;
    symmetrize(s);
    SmallCholesky<M> s_factor;
    if (!s_factor.compute(s)) continue;  // a track with no usable S takes nothing this round
    auto from = std::lower_bound(work.candidates.begin(), work.candidates.end(), p.x() - radius,
                                 [](const auto& c, double east) { return c.east < east; });
    double log_normaliser = 0.0;  // of the shared S
    bool normalised = false;
    for (auto c = from; c != work.candidates.end() && c->east <= p.x() + radius; ++c) {
      if ((c->position - p).norm() > reach * (track_std + c->std_m)) continue;
      if (track_holds_address && mask.is_addressed(c->index)) continue;
      const Vector<M> nu =
          sensor.residual(fixed_detection<M>(scan.detections[c->index]), predicted);
      double nis = 0.0;
      double normaliser = 0.0;  // -1/2 log det(2 pi S)
      if (reports_own_noise) {
        // A detection whose report states its own σ has an S of its own (Scan::reported_std).
        Covariance<M> own =
            projected + reported_noise<M>(noise, reported_std_at(scan.reported_std, c->index));
        symmetrize(own);
        SmallCholesky<M> own_factor;
        if (!own_factor.compute(own)) continue;
        nis = nu.dot(own_factor.solve(nu));
        if (with_densities) normaliser = -0.5 * (log_2pi_m + own_factor.log_determinant());
      } else {
        nis = nu.dot(s_factor.solve(nu));
        if (with_densities && !normalised && nis <= gate) {
          log_normaliser = -0.5 * (log_2pi_m + s_factor.log_determinant());
          normalised = true;  // the track's S: once, when a pair of it first gates
        }
        normaliser = log_normaliser;
      }
      if (nis > gate) continue;
      out.pairs.push_back(
          {static_cast<int>(t), static_cast<int>(c->index), nis, normaliser - 0.5 * nis});
    }
  }
}

}  // namespace skyfuse
