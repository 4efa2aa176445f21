#pragma once
/// \file
/// A secondary (Mode S) surveillance radar: it interrogates the aircraft's transponder and
/// measures the reply's range and azimuth, and the reply carries the altitude the aircraft
/// reports of itself (in 25 ft steps) — not an elevation angle, which a surveillance radar does
/// not measure usefully. With d = p - p_station and rho = |(d_x, d_y)|:
///
///   h(x) = [ |d|, atan2(d_y, d_x), p_z ]
///   dh/dp = [ d^T / |d| ;  [-d_y, d_x, 0] / rho^2 ;  [0, 0, 1] ]
///
/// and dh/dx is zero outside the position block. The altitude is the scenario frame's height
/// (m), reported in whole steps of 25 ft (kAltitudeStepM): its noise should hold the step's
/// uniform error (kAltitudeStepM / sqrt(12) = 2.2 m) as well as the altimeter's.
///
/// What it can report: range in (0, kMaxRangeM], azimuth in [-pi, pi], altitude within
/// kMaxRangeM of the frame's origin; anything else on the wire is refused as out of range.

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
class RangeAzimuthAltitude {
 public:
  /// The name a scenario gives this sensor.
  static constexpr std::string_view kKind = "range_azimuth_altitude";
  static constexpr int kStateDim = StateDim;
  static constexpr int kMeasDim = 3;
  /// h depends on the position (the first three state components) only.
  static constexpr int kJacobianCols = 3;
  /// A ground station: the range and azimuth depend on where it stands.
  static constexpr bool kNeedsSite = true;
  static constexpr std::array<std::string_view, kMeasDim> kComponents = {"range_m", "azimuth_rad",
                                                                         "altitude_m"};
  using State = Vector<StateDim>;
  using Measurement = Vector<3>;

  static constexpr int kRange = 0;
  static constexpr int kAzimuth = 1;
  static constexpr int kAltitude = 2;
  /// Mode S reports its altitude in steps of 25 ft.
  static constexpr double kAltitudeStepM = 25.0 * 0.3048;

  RangeAzimuthAltitude() = default;
  explicit RangeAzimuthAltitude(const Vector3& station_position)
      : station_position_(station_position) {}

  /// Where the station stands (world frame, m).
  const Vector3& site() const { return station_position_; }

  /// Noise-free measurement of a target at position p (world frame, m), its altitude unrounded.
  Measurement measure_position(const Vector3& p) const {
    const Vector3 d = p - station_position_;
    return Measurement(d.norm(), std::atan2(d.y(), d.x()), p.z());
  }

  Measurement predict(const State& x) const { return measure_position(x.template head<3>()); }

  /// The position a measurement puts the target at: the reported altitude fixes the height, the
  /// range and azimuth the rest. A range shorter than the height difference (noise near the
  /// zenith) puts it straight above the station.
  Vector3 position_of(const Measurement& z) const {
    const double dz = z(kAltitude) - station_position_.z();
    const double horizontal = std::sqrt(std::max(z(kRange) * z(kRange) - dz * dz, 0.0));
    return Vector3(station_position_.x() + horizontal * std::cos(z(kAzimuth)),
                   station_position_.y() + horizontal * std::sin(z(kAzimuth)), z(kAltitude));
  }

  /// Analytic dh/dx. Directly above the station (rho = 0) the azimuth is undefined: its row is
  /// left zero instead of dividing by zero.
  Jacobian<3, StateDim> jacobian(const State& x) const {
    const Vector3 d = x.template head<3>() - station_position_;
    const double rho_sq = d.x() * d.x() + d.y() * d.y();
    const double range = d.norm();
    Jacobian<3, StateDim> h = Jacobian<3, StateDim>::Zero();
    if (range > 0.0) h.template block<1, 3>(kRange, 0) = d.transpose() / range;
    if (rho_sq > 0.0) {
      h(kAzimuth, 0) = -d.y() / rho_sq;
      h(kAzimuth, 1) = d.x() / rho_sq;
    }
    h(kAltitude, 2) = 1.0;
    return h;
  }

  /// z - z_pred with the azimuth taken the short way round the +-pi cut.
  static Measurement residual(const Measurement& z, const Measurement& z_pred) {
    Measurement nu = z - z_pred;
    nu(kAzimuth) = wrap_angle(nu(kAzimuth));
    return nu;
  }

  /// A noisy value as the radar reports it: azimuth wrapped into (-pi, pi], altitude rounded
  /// to the nearest 25 ft.
  static Measurement to_reported(Measurement z) {
    z(kAzimuth) = wrap_angle(z(kAzimuth));
    z(kAltitude) = std::round(z(kAltitude) / kAltitudeStepM) * kAltitudeStepM;
    return z;
  }

  /// Whether z is something this sensor can report: kNonFinite or kOutOfRange if not.
  static std::optional<DropKind> check_reported(const Measurement& z) {
    if (!z.allFinite()) return DropKind::kNonFinite;
    const double range = z(kRange);
    if (!(range > 0.0 && range <= kMaxRangeM) || std::abs(z(kAzimuth)) > std::numbers::pi ||
        std::abs(z(kAltitude)) > kMaxRangeM) {
      return DropKind::kOutOfRange;
    }
    return std::nullopt;
  }

 private:
  Vector3 station_position_ = Vector3::Zero();
};

}  // namespace skyfuse
