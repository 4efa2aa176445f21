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
/// and dh/dx is zero outside the position block: the range and azimuth rows are the 3-D radar's
/// (range_azimuth_elevation.hpp), which this sensor computes them with. The altitude is the
/// scenario frame's height (m), reported in whole steps of 25 ft (kAltitudeStepM): its noise should
/// hold the step's uniform error (kAltitudeStepM / sqrt(12) = 2.2 m) as well as the altimeter's.
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
#include "skyfuse/models/range_azimuth_elevation.hpp"
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

  static constexpr int kRange = RangeAzimuthElevation<StateDim>::kRange;
  static constexpr int kAzimuth = RangeAzimuthElevation<StateDim>::kAzimuth;
  static constexpr int kAltitude = 2;
  /// Mode S reports its altitude in steps of 25 ft.
  static constexpr double kAltitudeStepM = 25.0 * 0.3048;

  RangeAzimuthAltitude() = default;
  explicit RangeAzimuthAltitude(const Vector3& station_position) : radar_(station_position) {}

  /// Where the station stands (world frame, m).
  const Vector3& site() const { return radar_.site(); }

  /// Noise-free measurement of a target at position p (world frame, m), its altitude unrounded.
  Measurement measure_position(const Vector3& p) const {
    Measurement z = radar_.measure_position(p);
    z(kAltitude) = p.z();
    return z;
  }

  Measurement predict(const State& x) const { return measure_position(x.template head<3>()); }

  /// The position a measurement puts the target at: the reported altitude fixes the height, the
  /// range and azimuth the rest. A range shorter than the height difference (noise near the
  /// zenith) puts it straight above the station.
  Vector3 position_of(const Measurement& z) const {
    const Vector3& site = radar_.site();
    const double dz = z(kAltitude) - site.z();
    const double horizontal = std::sqrt(std::max(z(kRange) * z(kRange) - dz * dz, 0.0));
    return Vector3(site.x() + horizontal * std::cos(z(kAzimuth)),
                   site.y() + horizontal * std::sin(z(kAzimuth)), z(kAltitude));
  }

  /// Analytic dh/dx: the 3-D radar's range and azimuth rows (zero azimuth row directly above
  /// the station), and the altitude's, which reads p_z.
  Jacobian<3, StateDim> jacobian(const State& x) const {
    Jacobian<3, StateDim> h = radar_.jacobian(x);
    h.row(kAltitude).setZero();
    h(kAltitude, 2) = 1.0;
    return h;
  }

  /// z - z_pred with the azimuth taken the short way round the +-pi cut, as the 3-D radar's.
  static Measurement residual(const Measurement& z, const Measurement& z_pred) {
    return Radar::residual(z, z_pred);
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
  using Radar = RangeAzimuthElevation<StateDim>;
  Radar radar_;
};

}  // namespace skyfuse
