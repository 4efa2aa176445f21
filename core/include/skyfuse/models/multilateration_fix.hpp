#pragma once
/// \file
/// Where a transponder is, from the differences of its reply's ranges to a group of receivers:
/// the multilateration fix (models/multilateration.hpp). Receiver 0 is the reference; the
/// measured d_i = |p - s_i| - |p - s_0| (m, c times the time difference of arrival), i >= 1.
///
/// Two steps, each its own function so a test can check it alone:
///
/// 1. A closed-form start. With r_0 = |p - s_0| and the sites taken relative to s_0
///    (t_i = s_i - s_0, q = p - s_0), squaring r_0 + d_i = |q - t_i| gives for each receiver
///    a line linear in (q, r_0):
///
///      2 t_i^T q + 2 d_i r_0 = |t_i|^2 - d_i^2.
///
///    Ground receivers stand nearly in a plane, so the height column t_iz is small beside the
///    horizontal ones and a least-squares solve in all four unknowns would be ill-conditioned.
///    The start solves for (q_x, q_y, r_0) with q_z moved to the right-hand side, then sets
///    q_z = +sqrt(r_0^2 - q_x^2 - q_y^2) (above the reference: the mirror solution under the
///    receivers' plane fits as well), and repeats a few times.
/// 2. Gauss-Newton on the weighted least squares sum_i (d_i - h_i(p))^2 / var_i from that
///    start, damped (Levenberg-Marquardt) until each step lowers the cost: the height is the
///    weak coordinate of ground receivers, and undamped steps overshoot along its curved valley.
///
/// The fix is the minimum no lower than the lowest receiver. Ground receivers see an aircraft
/// and its mirror under their plane almost alike, and for an aircraft low over far receivers
/// the noise often favours the mirror; nothing flies there, so the search stays above it (a
/// step that would leave holds the height at the floor and moves along it).
///
/// Exact data (no noise, at least four receivers not all in a line) gives the position back;
/// the fix's covariance is (H^T R^-1 H)^-1 at it, which picture/initiation.hpp computes
/// from the sensor's Jacobian.

#include <span>

#include "skyfuse/core/types.hpp"

namespace skyfuse {

/// What the solver found.
struct MultilaterationFix {
  Vector3 position = Vector3::Zero();
  /// The weighted sum of squared residuals at `position`.
  double cost = 0.0;
  int iterations = 0;
  /// Whether the last step was below its tolerance (1e-6 m) or no step lowered the cost; a
  /// false fix is the best point found in the iterations allowed.
  bool converged = false;
};

/// The predicted range differences h_i(p) = |p - s_i| - |p - s_0| for receivers s (s[0] the
/// reference), written into `out` (size s.size() - 1).
void range_differences(std::span<const Vector3> receivers, const Vector3& p, std::span<double> out);

/// Step 1: the closed-form start. `differences` has one entry per receiver after the first.
Vector3 multilateration_start(std::span<const Vector3> receivers,
                              std::span<const double> differences);

/// Steps 1 and 2: the weighted least-squares fix, each difference with variance `variances`.
MultilaterationFix solve_multilateration(std::span<const Vector3> receivers,
                                         std::span<const double> differences,
                                         std::span<const double> variances);

}  // namespace skyfuse
