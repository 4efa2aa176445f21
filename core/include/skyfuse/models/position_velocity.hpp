#pragma once
/// \file
/// A receiver on the target that reports its own position and velocity, as a GPS receiver does
/// (paper 003) or an aircraft broadcasting ADS-B to the ground:
///
///   z = [p; v] + noise,   h(x) = x[0:6],   dh/dx = [I6 0].
///
/// Linear, so the EKF update with it is the Kalman filter's. Every 3-D model of this project
/// keeps the position in state entries 0-2 and the velocity in 3-5, which is what it reads.
///
/// What it can report: a position within kMaxRangeM of the origin and a speed up to
/// kMaxSpeedMps; anything else on the wire is refused as out of range.

#include <array>
#include <optional>
#include <string_view>

#include "skyfuse/core/types.hpp"
#include "skyfuse/validation/drop_kind.hpp"
#include "skyfuse/validation/physical_bounds.hpp"

namespace skyfuse {

template <int StateDim>
class PositionVelocity {
 public:
  /// The name a scenario gives this sensor.
  static constexpr std::string_view kKind = "position_velocity";
  static constexpr int kStateDim = StateDim;
  static constexpr int kMeasDim = 6;
  /// h reads the position and velocity, the first six state components.
  static constexpr int kJacobianCols = 6;
  /// It rides on the target: no site.
  static constexpr bool kNeedsSite = false;
  /// What the aircraft itself reports of where it is (ADS-B, Remote ID): a registration takes
  /// it as the reference the other stations' biases are measured against
  /// (LeastSquaresRegistration::learn, picture/registrations/least_squares.hpp).
  static constexpr bool kReportsOwnState = true;
  static constexpr std::array<std::string_view, kMeasDim> kComponents = {
      "x_m", "y_m", "z_m", "vx_mps", "vy_mps", "vz_mps"};
  using State = Vector<StateDim>;
  using Measurement = Vector<kMeasDim>;

  PositionVelocity() = default;
  /// Every sensor is built from its site; this one has none and ignores it.
  explicit PositionVelocity(const Vector3& /*site*/) {}

  /// The origin: there is no site to report, and nothing to check.
  Vector3 site() const { return Vector3::Zero(); }

  Measurement predict(const State& x) const { return x.template head<kMeasDim>(); }
  /// The position a measurement puts the target at (picture/initiation.hpp).
  static Vector3 position_of(const Measurement& z) { return z.template head<3>(); }
  /// The velocity a measurement reports (picture/initiation.hpp), entries 3-5.
  static constexpr int kVelocityEntries = 3;
  static Vector3 velocity_of(const Measurement& z) { return z.template segment<3>(3); }

  Jacobian<kMeasDim, StateDim> jacobian(const State& /*x*/) const {
    Jacobian<kMeasDim, StateDim> h = Jacobian<kMeasDim, StateDim>::Zero();
    h.template leftCols<kMeasDim>().setIdentity();
    return h;
  }

  static Measurement residual(const Measurement& z, const Measurement& z_pred) {
    return z - z_pred;
  }

  /// Position and velocity are reported as measured.
  static Measurement to_reported(const Measurement& z) { return z; }

  /// Whether z is something this sensor can report: kNonFinite or kOutOfRange if not.
  static std::optional<DropKind> check_reported(const Measurement& z) {
    if (!z.allFinite()) return DropKind::kNonFinite;
    if (z.template head<3>().norm() > kMaxRangeM || z.template tail<3>().norm() > kMaxSpeedMps) {
      return DropKind::kOutOfRange;
    }
    return std::nullopt;
  }
};

}  // namespace skyfuse
