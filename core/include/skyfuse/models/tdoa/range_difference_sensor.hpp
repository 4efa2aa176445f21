#pragma once
/// \file
/// A TDOA receiver (paper 002): the difference of the target's ranges to this receiver and to
/// the reference receiver at the origin, h(x) = |dp - P_j| - |dp|, of the horizontal position
/// dp (the first two state entries), with P_j the receiver's horizontal site. In paper 002's
/// frame the origin is the reference UAV and the state is the target's position relative to it;
/// the formation flies rigidly, so every site is fixed there. Its gradient in dp is
/// (dp - P_j)^T / |dp - P_j| - dp^T / |dp|. A scenario names it `tdoa_range_difference`.

#include <array>
#include <cmath>
#include <optional>
#include <string_view>

#include "skyfuse/core/types.hpp"
#include "skyfuse/validation/drop_kind.hpp"
#include "skyfuse/validation/physical_bounds.hpp"

namespace skyfuse {

template <int N>
class RangeDifferenceSensor {
 public:
  static constexpr std::string_view kKind = "tdoa_range_difference";
  static constexpr int kStateDim = N;
  static constexpr int kMeasDim = 1;
  /// Only the horizontal position's columns of the Jacobian are non-zero.
  static constexpr int kJacobianCols = 2;
  /// It reads a horizontal position (models/state_position.hpp): paper 002's relative state's,
  /// or a 3-D model's first two entries.
  static constexpr int kPositionDim = 2;
  static constexpr bool kNeedsSite = true;
  static constexpr std::array<std::string_view, kMeasDim> kComponents = {"range_difference_m"};
  using State = Vector<N>;
  using Measurement = Vector<kMeasDim>;

  RangeDifferenceSensor() = default;
  /// The site's height is kept (it is the scenario's) but not used: the measurement is planar.
  explicit RangeDifferenceSensor(const Vector3& site) : site_(site) {}
  explicit RangeDifferenceSensor(const Vector<2>& offset) : site_(offset.x(), offset.y(), 0.0) {}

  Vector3 site() const { return site_; }
  Vector<2> offset() const { return site_.head<2>(); }

  Vector<1> predict(const Vector<N>& x) const {
    const Vector<2> dp = x.template head<2>();
    return Vector<1>((dp - offset()).norm() - dp.norm());
  }
  Jacobian<1, N> jacobian(const Vector<N>& x) const {
    const Vector<2> dp = x.template head<2>();
    Jacobian<1, N> h = Jacobian<1, N>::Zero();
    h.template head<2>() = ((dp - offset()) / (dp - offset()).norm() - dp / dp.norm()).transpose();
    return h;
  }
  static Vector<1> residual(const Vector<1>& z, const Vector<1>& predicted) {
    return z - predicted;
  }
  /// A range difference is reported as measured.
  static Vector<1> to_reported(const Vector<1>& z) { return z; }
  /// A range difference is at most the baseline in magnitude, plus noise; without the site at
  /// hand only a non-finite value or one beyond kMaxRangeM is refused here (the site check of
  /// every received measurement pins the baseline).
  static std::optional<DropKind> check_reported(const Vector<1>& z) {
    if (!z.allFinite()) return DropKind::kNonFinite;
    if (std::abs(z(0)) > kMaxRangeM) return DropKind::kOutOfRange;
    return std::nullopt;
  }

 private:
  Vector3 site_ = Vector3::Zero();
};

}  // namespace skyfuse
