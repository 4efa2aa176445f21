#include "skyfuse/validation/sample_checks.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "skyfuse/core/small_cholesky.hpp"

namespace skyfuse {

std::optional<DropKind> check_increment(const InformationIncrement<9>& increment) {
  if (!increment.delta_information.allFinite() || !increment.delta_vector.allFinite()) {
    return DropKind::kNonFinite;
  }
  if (increment.delta_information.cwiseAbs().maxCoeff() > kMaxInformation ||
      increment.delta_vector.cwiseAbs().maxCoeff() > kMaxInformation * kMaxRangeM) {
    return DropKind::kOutOfRange;
  }
  // dQ = H^T R^-1 H is singular (rank 3 for one sensor), so a Cholesky cannot test it; the
  // eigenvalues of a 9 x 9 cost a few microseconds, once per received sample. They are taken
  // of dQ scaled to a largest entry of 1: near the largest double they overflow to +-Inf, and
  // -Inf < -1e-9 * Inf is false, which let an indefinite dQ through.
  const double largest_entry = increment.delta_information.cwiseAbs().maxCoeff();
  if (largest_entry == 0.0) return std::nullopt;
  const Eigen::SelfAdjointEigenSolver<Covariance<9>> eigen(
      increment.delta_information / largest_entry, Eigen::EigenvaluesOnly);
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

std::optional<DropKind> check_observation(
    const StationObservation<RangeAzimuthElevation<9>>& observation) {
  if (!observation.z.allFinite() || !observation.noise.allFinite() ||
      !observation.sensor.station_position().allFinite()) {
    return DropKind::kNonFinite;
  }
  SmallCholesky<3> factor;
  if (!factor.compute(observation.noise)) return DropKind::kNotPositive;
  constexpr double kPi = std::numbers::pi;
  using Sensor = RangeAzimuthElevation<9>;
  const double range = observation.z(Sensor::kRange);
  const double azimuth = observation.z(Sensor::kAzimuth);
  const double elevation = observation.z(Sensor::kElevation);
  if (observation.sensor.station_position().norm() > kMaxRangeM) return DropKind::kOutOfRange;
  if (!(range > 0.0 && range <= kMaxRangeM) || std::abs(azimuth) > kPi ||
      std::abs(elevation) > kPi / 2.0) {
    return DropKind::kOutOfRange;
  }
  return std::nullopt;
}

}  // namespace skyfuse
