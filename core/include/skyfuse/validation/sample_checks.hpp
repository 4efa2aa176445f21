#pragma once
/// \file
/// Content checks a receiver applies to a sample before it may be fused: the checks that need
/// no knowledge of the run (the run id, step window and station ids are checked by the
/// receiver and its StepCollector). Each returns the first problem found, or nothing.

#include <algorithm>
#include <cmath>
#include <optional>
#include <type_traits>

#include "skyfuse/core/llt_success.hpp"
#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/tracking/peer_contribution.hpp"
#include "skyfuse/validation/drop_kind.hpp"
#include "skyfuse/validation/physical_bounds.hpp"

namespace skyfuse {

namespace detail {

// A sufficient test for check_increment's rule, at a third of the eigenvalues' cost
// (CheckIncrement 1.26 -> 0.39 us; the eigenvalues were ~3 % of a station's CPU at M = 8, paid
// for every increment received). dQ = H^T R^-1 H is singular (rank 3 for one sensor), so it
// has no Cholesky factor itself; dQ + t I has one exactly when every eigenvalue of dQ is above
// -t. With t below 1e-9 times the largest eigenvalue magnitude the rule holds whenever the
// factorisation succeeds. That magnitude is bounded from below by every |diagonal entry| and
// by the Frobenius norm / sqrt(N) (the norm is the root of the sum of the N squared
// eigenvalues); t is 0.9e-9 times the larger bound, and the 0.1e-9 left over covers the
// factorisation's rounding (~1e-14 of the norm at 9 x 9).
template <int N>
bool passes_shifted_cholesky(const Covariance<N>& dq) {
  const double magnitude_bound =
      std::max(dq.diagonal().cwiseAbs().maxCoeff(), dq.norm() / std::sqrt(double{N}));
  const Covariance<N> shifted = dq + Covariance<N>::Identity() * (0.9e-9 * magnitude_bound);
  SmallCholesky<N> factor;
  return factor.compute(shifted);
}

// The largest state the out-of-line eigenvalue test takes: the wire's (kMaxStateDim in
// idl/skyfuse_wire.idl).
inline constexpr int kMaxCheckedDim = 16;
// A matrix of any size up to that, held in place: no heap allocation.
using BoundedSymmetric =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCheckedDim, kMaxCheckedDim>;

// check_increment's rule decided by the eigenvalues of `scaled` (dQ scaled to a largest entry
// of 1), when passes_shifted_cholesky could not show it: kNotPositive, or nothing. Out of line
// and of one bounded size, so that one eigen-solver is compiled for every N, in one file:
// compiled per N in every file that checks an increment it made a second or more of each, and
// it runs only for increments the cheap test does not pass (an indefinite one, or one at its
// edge).
std::optional<DropKind> check_eigenvalues(const BoundedSymmetric& scaled);

}  // namespace detail

/// dQ and dy finite; their entries within kMaxInformation (dy: times kMaxRangeM); dQ positive
/// semi-definite (smallest eigenvalue >= -1e-9 times the largest magnitude: rounding in
/// H^T R^-1 H is allowed, a negative direction is not).
template <int N>
std::optional<DropKind> check_increment(const InformationIncrement<N>& increment) {
  if (!increment.delta_information.allFinite() || !increment.delta_vector.allFinite()) {
    return DropKind::kNonFinite;
  }
  if (increment.delta_information.cwiseAbs().maxCoeff() > kMaxInformation ||
      increment.delta_vector.cwiseAbs().maxCoeff() > kMaxInformation * kMaxRangeM) {
    return DropKind::kOutOfRange;
  }
  // The rule: the smallest eigenvalue of dQ is at least -1e-9 times the largest magnitude.
  // It is tested on dQ scaled to a largest entry of 1: near the largest double the
  // eigenvalues overflow to +-Inf, and -Inf < -1e-9 * Inf is false, which let an indefinite
  // dQ through.
  const double largest_entry = increment.delta_information.cwiseAbs().maxCoeff();
  if (largest_entry == 0.0) return std::nullopt;
  const Covariance<N> scaled = increment.delta_information / largest_entry;
  if (detail::passes_shifted_cholesky<N>(scaled)) return std::nullopt;
  // Not shown positive semi-definite by the cheap test: decide by the eigenvalues themselves.
  static_assert(N <= detail::kMaxCheckedDim);
  return detail::check_eigenvalues(scaled);
}

/// Mean and covariance finite and within kMaxStateMagnitude; covariance positive definite (a
/// prior or a track a peer may adopt, a posterior the soak checks). Fixed sizes factorise with
/// SmallCholesky, run-time sizes with Eigen's LLT.
template <typename Mean, typename Cov>
std::optional<DropKind> check_estimate(const Eigen::MatrixBase<Mean>& mean,
                                       const Eigen::MatrixBase<Cov>& covariance) {
  if (!mean.allFinite() || !covariance.allFinite()) return DropKind::kNonFinite;
  if (mean.cwiseAbs().maxCoeff() > kMaxStateMagnitude ||
      covariance.cwiseAbs().maxCoeff() > kMaxStateMagnitude) {
    return DropKind::kOutOfRange;
  }
  constexpr int N = Cov::RowsAtCompileTime;
  if constexpr (N == Eigen::Dynamic) {
    const Eigen::LLT<Eigen::MatrixXd> factor(covariance);
    if (!llt_succeeded(factor)) return DropKind::kNotPositive;
  } else {
    SmallCholesky<N> factor;
    if constexpr (std::is_same_v<Cov, Covariance<N>>) {
      if (!factor.compute(covariance.derived())) return DropKind::kNotPositive;
    } else {
      if (!factor.compute(Covariance<N>(covariance))) return DropKind::kNotPositive;
    }
  }
  return std::nullopt;
}

template <int N>
std::optional<DropKind> check_estimate(const GaussianState<N>& estimate) {
  return check_estimate(estimate.mean, estimate.covariance);
}

/// The increment as check_increment(), then the prior it travels with as check_estimate().
template <int N>
std::optional<DropKind> check_contribution(const PeerContribution<N>& contribution) {
  if (const auto why = check_increment(contribution.increment)) return why;
  return check_estimate(contribution.prior);
}

/// The mode probabilities of an IMM sample or track: finite, each in [0, 1], summing to 1 within
/// 1e-9 (the IMM normalises them; rounding leaves about 1e-16).
template <typename Probabilities>
std::optional<DropKind> check_mode_probabilities(const Probabilities& probabilities) {
  constexpr double kSumTolerance = 1e-9;
  if (!probabilities.allFinite()) return DropKind::kNonFinite;
  if ((probabilities.array() < 0.0).any() || (probabilities.array() > 1.0).any() ||
      std::abs(probabilities.sum() - 1.0) > kSumTolerance) {
    return DropKind::kOutOfRange;
  }
  return std::nullopt;
}

/// One station's bounds on its likelihood terms: 16 measured components of variance
/// 1e-27 .. 1e27.
inline constexpr int kMaxMeasurementDim = 16;
inline constexpr double kMaxLogDetNoise = 1.0e3;

/// The likelihood terms that travel with an IMM mode's increment: finite, nu^T R^-1 nu >= 0, a
/// measured dimension in [1, max_measurement_dim] and |log det R| within max_log_det_noise; or,
/// for a measurement screened out, all zero with a zero increment. The bounds are one
/// station's unless a sum of several is checked (validation/partial_sum_checks.hpp).
template <int N>
std::optional<DropKind> check_likelihood_terms(const LikelihoodTerms& terms,
                                               const InformationIncrement<N>& increment,
                                               int max_measurement_dim = kMaxMeasurementDim,
                                               double max_log_det_noise = kMaxLogDetNoise) {
  if (!std::isfinite(terms.weighted_innovation) || !std::isfinite(terms.log_det_noise)) {
    return DropKind::kNonFinite;
  }
  if (terms.measurement_dim == 0) {
    const bool all_zero = terms.weighted_innovation == 0.0 && terms.log_det_noise == 0.0 &&
                          increment.delta_information.isZero(0.0) &&
                          increment.delta_vector.isZero(0.0);
    return all_zero ? std::nullopt : std::optional(DropKind::kOutOfRange);
  }
  if (terms.weighted_innovation < 0.0 || terms.measurement_dim < 0 ||
      terms.measurement_dim > max_measurement_dim ||
      std::abs(terms.log_det_noise) > max_log_det_noise) {
    return DropKind::kOutOfRange;
  }
  return std::nullopt;
}

/// What a measurement's source must be, whatever it reports: R and the sensor's site finite, R
/// positive definite, the site within kMaxRangeM of the origin. A receiver checks it for every
/// sample that brings its own R and site; a station and the in-process run, whose R and site do
/// not change, check them once.
template <typename Sensor>
std::optional<DropKind> check_observation_source(const Sensor& sensor,
                                                 const Covariance<Sensor::kMeasDim>& noise) {
  if (!noise.allFinite() || !sensor.site().allFinite()) return DropKind::kNonFinite;
  SmallCholesky<Sensor::kMeasDim> factor;
  if (!factor.compute(noise)) return DropKind::kNotPositive;
  if (sensor.site().norm() > kMaxRangeM) return DropKind::kOutOfRange;
  return std::nullopt;
}

/// z finite, the source as check_observation_source(), and z something the sensor can report
/// (Sensor::check_reported).
template <typename Sensor>
std::optional<DropKind> check_observation(const StationObservation<Sensor>& observation) {
  if (!observation.z.allFinite()) return DropKind::kNonFinite;
  if (const auto why = check_observation_source(observation.sensor, observation.noise)) return why;
  return Sensor::check_reported(observation.z);
}

/// kWrongSite unless the sensor stands where the scenario puts `station` (bit for bit: the
/// station and every receiver read the same scenario). A measurement that claims another site
/// is not that station's, whatever it says; a sensor without a site reports the origin.
template <typename Sensor>
std::optional<DropKind> check_site(const Sensor& sensor, const StationConfig& station) {
  if (sensor.site() != station.position_m) return DropKind::kWrongSite;
  return std::nullopt;
}

/// A measurement that claims to be `station`'s, as the center and the recorder check it: its
/// content (check_observation), then the sensor the scenario gives that station (kOutOfRange
/// for another kind), then its site (check_site). `station` null: an id that is no
/// participant's, which the step collector refuses; only the content is checked.
template <typename Sensor>
std::optional<DropKind> check_station_measurement(const StationObservation<Sensor>& observation,
                                                  const StationConfig* station) {
  if (const auto why = check_observation(observation)) return why;
  if (station == nullptr) return std::nullopt;
  if (Sensor::kKind != station->sensor.kind) return DropKind::kOutOfRange;
  return check_site(observation.sensor, *station);
}

}  // namespace skyfuse
