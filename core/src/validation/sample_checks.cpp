#include "skyfuse/validation/sample_checks.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "skyfuse/core/small_cholesky.hpp"

namespace skyfuse {
namespace {

// A sufficient test for check_increment's rule, at a third of the eigenvalues' cost
// (CheckIncrement 1.26 -> 0.39 us; the eigenvalues were ~3 % of a station's CPU at M = 8, paid
// for every increment received). dQ = H^T R^-1 H is singular (rank 3 for one sensor), so it
// has no Cholesky factor itself; dQ + t I has one exactly when every eigenvalue of dQ is above
// -t. With t below 1e-9 times the largest eigenvalue magnitude the rule holds whenever the
// factorisation succeeds. That magnitude is bounded from below by every |diagonal entry| and
// by the Frobenius norm / 3 (the norm is the root of the sum of the nine squared eigenvalues);
// t is 0.9e-9 times the larger bound, and the 0.1e-9 left over covers the factorisation's
// rounding (~1e-14 of the norm at 9 x 9).
bool passes_shifted_cholesky(const Covariance<9>& dq) {
  const double magnitude_bound = std::max(dq.diagonal().cwiseAbs().maxCoeff(), dq.norm() / 3.0);
  const Covariance<9> shifted = dq + Covariance<9>::Identity() * (0.9e-9 * magnitude_bound);
  SmallCholesky<9> factor;
  return factor.compute(shifted);
}

}  // namespace

std::optional<DropKind> check_increment(const InformationIncrement<9>& increment) {
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
  const Covariance<9> scaled = increment.delta_information / largest_entry;
  if (passes_shifted_cholesky(scaled)) return std::nullopt;
  // Not shown positive semi-definite by the cheap test: decide by the eigenvalues themselves.
  const Eigen::SelfAdjointEigenSolver<Covariance<9>> eigen(scaled, Eigen::EigenvaluesOnly);
  if (eigen.info() != Eigen::Success) return DropKind::kNotPositive;
  const double smallest = eigen.eigenvalues().minCoeff();
  const double scale = eigen.eigenvalues().cwiseAbs().maxCoeff();
  if (smallest < -1e-9 * scale) return DropKind::kNotPositive;
  return std::nullopt;
}

std::optional<DropKind> check_estimate(const GaussianState<9>& estimate) {
  if (!estimate.mean.allFinite() || !estimate.covariance.allFinite()) return DropKind::kNonFinite;
  if (estimate.mean.cwiseAbs().maxCoeff() > kMaxStateMagnitude ||
      estimate.covariance.cwiseAbs().maxCoeff() > kMaxStateMagnitude) {
    return DropKind::kOutOfRange;
  }
  SmallCholesky<9> factor;
  if (!factor.compute(estimate.covariance)) return DropKind::kNotPositive;
  return std::nullopt;
}

std::optional<DropKind> check_contribution(const PeerContribution& contribution) {
  if (const auto why = check_increment(contribution.increment)) return why;
  return check_estimate(contribution.prior);
}

std::optional<DropKind> check_reported_values(const Vector3& z) {
  if (!z.allFinite()) return DropKind::kNonFinite;
  constexpr double kPi = std::numbers::pi;
  using Sensor = RangeAzimuthElevation<9>;
  const double range = z(Sensor::kRange);
  if (!(range > 0.0 && range <= kMaxRangeM) || std::abs(z(Sensor::kAzimuth)) > kPi ||
      std::abs(z(Sensor::kElevation)) > kPi / 2.0) {
    return DropKind::kOutOfRange;
  }
  return std::nullopt;
}

std::optional<DropKind> check_observation(
    const StationObservation<RangeAzimuthElevation<9>>& observation) {
  if (!observation.z.allFinite() || !observation.noise.allFinite() ||
      !observation.sensor.station_position().allFinite()) {
    return DropKind::kNonFinite;
  }
  SmallCholesky<3> factor;
  if (!factor.compute(observation.noise)) return DropKind::kNotPositive;
  if (observation.sensor.station_position().norm() > kMaxRangeM) return DropKind::kOutOfRange;
  return check_reported_values(observation.z);
}

}  // namespace skyfuse
