#pragma once
/// \file
/// A multilateration group: kReceivers ground receivers time one transponder reply, and the
/// group reports the differences of its arrival times at receivers 1..5 and at the reference
/// receiver 0, as range differences (m, c times the time difference), with the address the
/// reply carries. Paper 002's TDOA (models/tdoa/range_difference_sensor.hpp) in three
/// dimensions, for a fixed group. With s_i the receivers' sites:
///
///   h_i(x) = |p - s_i| - |p - s_0|,        i = 1..5
///   dh_i/dp = (p - s_i)^T / |p - s_i| - (p - s_0)^T / |p - s_0|
///
/// and dh/dx is zero outside the position block. Each difference's noise is its own (the
/// scenario gives one standard deviation per receiver pair); correlated arrival-time errors
/// would need a full R, which the simulation does not draw.
///
/// One reply fixes a position (picture/fixes_position.hpp): position_of solves the
/// weighted least squares from a closed-form start (models/multilateration_fix.hpp), weighting
/// the differences by the scenario's nominal standard deviations (a station's run scale
/// multiplies every variance alike and moves no minimum). Receivers on the ground stand almost
/// in a plane, so the height is the fix's weakest coordinate and the solution is taken above
/// the reference receiver; the fix's covariance (picture/initiation.hpp) says how weak.
///
/// The station's position is the reference receiver; `sensor.receivers_m` in the scenario
/// lists the other five. What it can report: every difference finite and no larger than
/// kMaxRangeM; anything else on the wire is refused.

#include <array>
#include <cmath>
#include <optional>
#include <span>
#include <string_view>

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/multilateration_fix.hpp"
#include "skyfuse/validation/drop_kind.hpp"
#include "skyfuse/validation/physical_bounds.hpp"

namespace skyfuse {

template <int StateDim>
class Multilateration {
 public:
  /// The name a scenario gives this sensor.
  static constexpr std::string_view kKind = "multilateration";
  static constexpr int kStateDim = StateDim;
  /// The reference and the receivers whose differences to it are measured.
  static constexpr int kReceivers = 6;
  static constexpr int kMeasDim = kReceivers - 1;
  /// h depends on the position (the first three state components) only.
  static constexpr int kJacobianCols = 3;
  /// A ground station: the reference receiver stands at the station's position.
  static constexpr bool kNeedsSite = true;
  static constexpr std::array<std::string_view, kMeasDim> kComponents = {
      "range_difference_1_m", "range_difference_2_m", "range_difference_3_m",
      "range_difference_4_m", "range_difference_5_m"};
  using State = Vector<StateDim>;
  using Measurement = Vector<kMeasDim>;
  using Receivers = std::array<Vector3, kReceivers>;

  Multilateration() = default;
  /// `reference`: receiver 0's site; `others`: receivers 1..5; `nominal_std`: each
  /// difference's standard deviation before a run's scale (m), which weights the fix.
  Multilateration(const Vector3& reference, std::span<const Vector3> others,
                  std::span<const double> nominal_std) {
    receivers_[0] = reference;
    for (int i = 0; i < kMeasDim; ++i) {
      receivers_[static_cast<std::size_t>(i) + 1] = others[static_cast<std::size_t>(i)];
      const double sigma = nominal_std[static_cast<std::size_t>(i)];
      variances_[static_cast<std::size_t>(i)] = sigma * sigma;
    }
  }

  /// The same group for a state of another dimension (an IMM's modes).
  template <int OtherDim>
  explicit Multilateration(const Multilateration<OtherDim>& other)
      : receivers_(other.receivers_), variances_(other.variances_) {}

  /// The reference receiver's site (world frame, m).
  const Vector3& site() const { return receivers_[0]; }
  const Receivers& receivers() const { return receivers_; }

  /// Noise-free measurement of a transponder at position p (world frame, m).
  Measurement measure_position(const Vector3& p) const {
    Measurement z;
    range_differences(receivers_, p, std::span<double>(z.data(), kMeasDim));
    return z;
  }

  Measurement predict(const State& x) const { return measure_position(x.template head<3>()); }

  /// The position one reply puts the transponder at: the weighted least-squares fix.
  Vector3 position_of(const Measurement& z) const {
    return solve_multilateration(receivers_, std::span<const double>(z.data(), kMeasDim),
                                 variances_)
        .position;
  }

  /// Analytic dh/dx. At a receiver's own site its row's gradient is undefined; that row is
  /// left without that receiver's term instead of dividing by zero.
  Jacobian<kMeasDim, StateDim> jacobian(const State& x) const {
    const Vector3 p = x.template head<3>();
    const Vector3 reference = unit_from(receivers_[0], p);
    Jacobian<kMeasDim, StateDim> h = Jacobian<kMeasDim, StateDim>::Zero();
    for (int i = 0; i < kMeasDim; ++i) {
      h.template block<1, 3>(i, 0) =
          (unit_from(receivers_[static_cast<std::size_t>(i) + 1], p) - reference).transpose();
    }
    return h;
  }

  static Measurement residual(const Measurement& z, const Measurement& z_pred) {
    return z - z_pred;
  }

  /// Differences are reported as measured.
  static Measurement to_reported(const Measurement& z) { return z; }

  /// Whether z is something this sensor can report: kNonFinite or kOutOfRange if not.
  static std::optional<DropKind> check_reported(const Measurement& z) {
    if (!z.allFinite()) return DropKind::kNonFinite;
    if (z.cwiseAbs().maxCoeff() > kMaxRangeM) return DropKind::kOutOfRange;
    return std::nullopt;
  }

 private:
  template <int>
  friend class Multilateration;

  // (p - s) / |p - s|, or zero at s itself.
  static Vector3 unit_from(const Vector3& s, const Vector3& p) {
    const Vector3 d = p - s;
    const double norm = d.norm();
    return norm > 0.0 ? Vector3(d / norm) : Vector3::Zero();
  }

  Receivers receivers_{};
  std::array<double, kMeasDim> variances_{1.0, 1.0, 1.0, 1.0, 1.0};
};

}  // namespace skyfuse
