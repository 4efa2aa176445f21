#pragma once
/// \file
/// Paper 002's TDOA measurement as the EKF sees it: one receiver's range difference
/// h(x) = |dp - P_j| - |dp| of the relative position dp = p_t - p_1 (the first two entries of
/// the state), with P_j = p_j - p_1 the receiver's offset from the reference UAV. Its gradient
/// in dp is (dp - P_j)^T / |dp - P_j| - dp^T / |dp|.

#include <optional>

#include "skyfuse/core/types.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse {

template <int N>
class RangeDifferenceSensor {
 public:
  static constexpr int kStateDim = N;
  static constexpr int kMeasDim = 1;
  /// Only the position columns of the Jacobian are non-zero.
  static constexpr int kJacobianCols = 2;

  explicit RangeDifferenceSensor(const Vector<2>& offset) : offset_(offset) {}

  Vector<1> predict(const Vector<N>& x) const {
    const Vector<2> dp = x.template head<2>();
    return Vector<1>((dp - offset_).norm() - dp.norm());
  }
  Jacobian<1, N> jacobian(const Vector<N>& x) const {
    const Vector<2> dp = x.template head<2>();
    Jacobian<1, N> h = Jacobian<1, N>::Zero();
    h.template head<2>() = ((dp - offset_) / (dp - offset_).norm() - dp / dp.norm()).transpose();
    return h;
  }
  static Vector<1> residual(const Vector<1>& z, const Vector<1>& predicted) {
    return z - predicted;
  }
  /// A range difference is at most the baseline |P_j| in magnitude (the triangle inequality);
  /// noise may take it a little past, so only a non-finite value is refused.
  static std::optional<DropKind> check_reported(const Vector<1>& z) {
    if (!z.allFinite()) return DropKind::kNonFinite;
    return std::nullopt;
  }
  const Vector<2>& offset() const { return offset_; }

 private:
  Vector<2> offset_;
};

}  // namespace skyfuse
