#pragma once
/// \file
/// A primary 2-D surveillance radar: it measures the slant range and the azimuth of an echo and
/// nothing of its height (a rotating fan beam has no usable elevation). With d = p - p_station
/// and rho = |(d_x, d_y)|:
///
///   h(x) = [ |d|, atan2(d_y, d_x) ]
///   dh/dp = [ d^T / |d| ;  [-d_y, d_x, 0] / rho^2 ]
///
/// the 3-D radar's first two rows (range_azimuth_elevation.hpp), which this sensor computes them
/// with. One detection leaves the height open, so the sensor carries the scenario's altitude band
/// (`sensor: {height_band_m: [low, high]}`) as a prior on the height: position_of puts an echo on
/// its range circle at the band's middle, and a track's fix from it holds the band as a uniform
/// spread of variance (high - low)^2 / 12 in the height (picture/initiation.hpp). Stations that
/// do measure a height (a 3-D radar, a Mode S altitude, a broadcast) outweigh that prior wherever
/// their fixes join a 2-D radar's.
///
/// What it can report: range in (0, kMaxRangeM], azimuth in [-pi, pi]; anything else on the wire
/// is refused as out of range.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string_view>

#include "skyfuse/core/angles.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/models/height_band.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/validation/drop_kind.hpp"
#include "skyfuse/validation/physical_bounds.hpp"

namespace skyfuse {

template <int StateDim>
class RangeAzimuth {
 public:
  /// The name a scenario gives this sensor.
  static constexpr std::string_view kKind = "range_azimuth";
  static constexpr int kStateDim = StateDim;
  static constexpr int kMeasDim = 2;
  /// h depends on the position (the first three state components) only.
  static constexpr int kJacobianCols = 3;
  /// A ground station: the range and azimuth depend on where it stands.
  static constexpr bool kNeedsSite = true;
  /// Its detections need the scenario's height band to place them (make_parts.hpp).
  static constexpr bool kAssumesHeight = true;
  static constexpr std::array<std::string_view, kMeasDim> kComponents = {"range_m", "azimuth_rad"};
  using State = Vector<StateDim>;
  using Measurement = Vector<2>;

  static constexpr int kRange = RangeAzimuthElevation<StateDim>::kRange;
  static constexpr int kAzimuth = RangeAzimuthElevation<StateDim>::kAzimuth;

  RangeAzimuth() = default;
  RangeAzimuth(const Vector3& station_position, const HeightBand& band)
      : radar_(station_position), band_(band) {}
  /// The same radar for a state of another size (the truth's, to simulate what it sees).
  template <int OtherDim>
  explicit RangeAzimuth(const RangeAzimuth<OtherDim>& other)
      : radar_(other.site()), band_(other.height_band()) {}

  /// Where the station stands (world frame, m).
  const Vector3& site() const { return radar_.site(); }
  /// The heights it assumes an echo comes from.
  const HeightBand& height_band() const { return band_; }

  /// Noise-free measurement of a target at position p (world frame, m).
  Measurement measure_position(const Vector3& p) const {
    return radar_.measure_position(p).template head<2>();
  }

  Measurement predict(const State& x) const { return measure_position(x.template head<3>()); }

  /// Where an echo is if it flies at the band's middle: on its range circle at that height. A
  /// range shorter than the height difference (an echo near the zenith) puts it straight above
  /// the station.
  Vector3 position_of(const Measurement& z) const {
    const Vector3& site = radar_.site();
    const double height = band_.middle_m();
    const double dz = height - site.z();
    const double horizontal = std::sqrt(std::max(z(kRange) * z(kRange) - dz * dz, 0.0));
    return Vector3(site.x() + horizontal * std::cos(z(kAzimuth)),
                   site.y() + horizontal * std::sin(z(kAzimuth)), height);
  }

  /// Analytic dh/dx: the 3-D radar's range and azimuth rows (a zero azimuth row directly above
  /// the station).
  Jacobian<2, StateDim> jacobian(const State& x) const {
    return radar_.jacobian(x).template topRows<2>();
  }

  /// z - z_pred with the azimuth taken the short way round the +-pi cut.
  static Measurement residual(const Measurement& z, const Measurement& z_pred) {
    Measurement nu = z - z_pred;
    nu(kAzimuth) = wrap_angle(nu(kAzimuth));
    return nu;
  }

  /// A noisy value as the radar reports it: the azimuth wrapped into (-pi, pi].
  static Measurement to_reported(Measurement z) {
    z(kAzimuth) = wrap_angle(z(kAzimuth));
    return z;
  }

  /// Whether z is something this sensor can report: kNonFinite or kOutOfRange if not.
  static std::optional<DropKind> check_reported(const Measurement& z) {
    if (!z.allFinite()) return DropKind::kNonFinite;
    const double range = z(kRange);
    if (!(range > 0.0 && range <= kMaxRangeM) || std::abs(z(kAzimuth)) > std::numbers::pi) {
      return DropKind::kOutOfRange;
    }
    return std::nullopt;
  }

 private:
  RangeAzimuthElevation<StateDim> radar_;
  HeightBand band_;
};

}  // namespace skyfuse
