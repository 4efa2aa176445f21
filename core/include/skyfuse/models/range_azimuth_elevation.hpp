#pragma once
/// \file
/// A ground station measuring range, azimuth and elevation to a target (paper 000, eq. 3,
/// with the azimuth misprint corrected to atan2(d_y, d_x)).
///
/// With d = p - p_station, rho = |(d_x, d_y)| and r = |d|:
///   h(x) = [ r, atan2(d_y, d_x), asin(d_z / r) ]
///   dh/dp = [ d^T / r ;
///             [-d_y, d_x, 0] / rho^2 ;
///             [-d_x d_z, -d_y d_z, rho^2] / (r^2 rho) ]
/// and dh/dx is zero outside the position block. The position must occupy the first three
/// entries of the state, as it does in every 3-D model of this project.
///
/// What it can report: range in (0, kMaxRangeM], azimuth in [-pi, pi], elevation in
/// [-pi/2, pi/2]; anything else on the wire is refused as out of range.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string_view>

#include "skyfuse/core/angles.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/validation/drop_kind.hpp"
#include "skyfuse/validation/physical_bounds.hpp"

namespace skyfuse {

template <int StateDim>
class RangeAzimuthElevation {
 public:
  /// The name a scenario gives this sensor.
  static constexpr std::string_view kKind = "range_azimuth_elevation";
  static constexpr int kStateDim = StateDim;
  static constexpr int kMeasDim = 3;
  /// h depends on the position (the first three state components) only.
  static constexpr int kJacobianCols = 3;
  /// A ground station: the measurement depends on where it stands.
  static constexpr bool kNeedsSite = true;
  /// The measured components, in order, as error messages and the docs name them.
  static constexpr std::array<std::string_view, kMeasDim> kComponents = {"range_m", "azimuth_rad",
                                                                         "elevation_rad"};
  using State = Vector<StateDim>;
  using Measurement = Vector<3>;

  static constexpr int kRange = 0;
  static constexpr int kAzimuth = 1;
  static constexpr int kElevation = 2;

  RangeAzimuthElevation() = default;
  explicit RangeAzimuthElevation(const Vector3& station_position)
      : station_position_(station_position) {}

  /// Where the station stands (world frame, m).
  const Vector3& site() const { return station_position_; }

  const Vector3& station_position() const { return station_position_; }

  /// Noise-free measurement of a target at position p (world frame, metres).
  Measurement measure_position(const Vector3& p) const {
    const Vector3 d = p - station_position_;
    const double range = d.norm();
    return Measurement(range, std::atan2(d.y(), d.x()), std::asin(d.z() / range));
  }

  Measurement predict(const State& x) const { return measure_position(x.template head<3>()); }

  /// The position a measurement puts the target at: one detection fixes a position, which is
  /// what a tracker of many aircraft starts a track from (picture/initiation.hpp).
  Vector3 position_of(const Measurement& z) const {
    const double horizontal = z(kRange) * std::cos(z(kElevation));
    return station_position_ + Vector3(horizontal * std::cos(z(kAzimuth)),
                                       horizontal * std::sin(z(kAzimuth)),
                                       z(kRange) * std::sin(z(kElevation)));
  }

  /// Analytic dh/dx. Directly above the station (rho = 0) the azimuth is undefined and the
  /// elevation has a cusp (it falls at 1/r in whichever horizontal direction the aircraft
  /// moves): both rows are left zero instead of dividing by zero, and only the range informs.
  Jacobian<3, StateDim> jacobian(const State& x) const {
    const Vector3 d = x.template head<3>() - station_position_;
    const double rho_sq = d.x() * d.x() + d.y() * d.y();
    const double range_sq = rho_sq + d.z() * d.z();
    const double range = std::sqrt(range_sq);
    const double rho = std::sqrt(rho_sq);

    Jacobian<3, StateDim> h = Jacobian<3, StateDim>::Zero();
    if (range > 0.0) h.template block<1, 3>(kRange, 0) = d.transpose() / range;
    if (rho > 0.0) {
      h(kAzimuth, 0) = -d.y() / rho_sq;
      h(kAzimuth, 1) = d.x() / rho_sq;
      const double scale = 1.0 / (range_sq * rho);
      h(kElevation, 0) = -d.x() * d.z() * scale;
      h(kElevation, 1) = -d.y() * d.z() * scale;
      h(kElevation, 2) = rho_sq * scale;
    }
    return h;
  }

  /// z - z_pred with the azimuth taken the short way round the +-pi cut. Elevation lives in
  /// [-pi/2, pi/2], so its difference never needs wrapping.
  static Measurement residual(const Measurement& z, const Measurement& z_pred) {
    Measurement nu = z - z_pred;
    nu(kAzimuth) = wrap_angle(nu(kAzimuth));
    return nu;
  }

  /// A noisy value as the sensor reports it: azimuth wrapped into (-pi, pi], elevation held
  /// within [-pi/2, pi/2] (past the zenith a sensor reports the zenith; otherwise every receiver
  /// would refuse the sample).
  static Measurement to_reported(Measurement z) {
    constexpr double kHalfPi = std::numbers::pi / 2.0;
    z(kAzimuth) = wrap_angle(z(kAzimuth));
    z(kElevation) = std::clamp(z(kElevation), -kHalfPi, kHalfPi);
    return z;
  }

  /// Whether z is something this sensor can report: kNonFinite or kOutOfRange if not.
  static std::optional<DropKind> check_reported(const Measurement& z) {
    if (!z.allFinite()) return DropKind::kNonFinite;
    constexpr double kPi = std::numbers::pi;
    const double range = z(kRange);
    if (!(range > 0.0 && range <= kMaxRangeM) || std::abs(z(kAzimuth)) > kPi ||
        std::abs(z(kElevation)) > kPi / 2.0) {
      return DropKind::kOutOfRange;
    }
    return std::nullopt;
  }

 private:
  Vector3 station_position_ = Vector3::Zero();
};

}  // namespace skyfuse
