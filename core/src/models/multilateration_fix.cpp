#include "skyfuse/models/multilateration_fix.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <vector>

namespace skyfuse {
namespace {

constexpr int kStartRounds = 6;
constexpr int kMaxIterations = 500;
constexpr double kInitialDamping = 1e-3;
constexpr double kMinDamping = 1e-9;
constexpr double kMaxDamping = 1e12;
constexpr double kStepToleranceM = 1e-6;
// Heights above the lowest receiver to descend from as well as from the closed-form start.
constexpr std::array<double, 4> kRestartHeightsM = {0.0, 300.0, 1500.0, 6000.0};

double weighted_cost(std::span<const Vector3> receivers, std::span<const double> differences,
                     std::span<const double> variances, const Vector3& p,
                     std::span<double> predicted) {
  range_differences(receivers, p, predicted);
  double cost = 0.0;
  for (std::size_t i = 0; i < differences.size(); ++i) {
    const double e = differences[i] - predicted[i];
    cost += e * e / variances[i];
  }
  return cost;
}

}  // namespace

void range_differences(std::span<const Vector3> receivers, const Vector3& p,
                       std::span<double> out) {
  assert(out.size() + 1 == receivers.size());
  const double reference = (p - receivers[0]).norm();
  for (std::size_t i = 1; i < receivers.size(); ++i) {
    out[i - 1] = (p - receivers[i]).norm() - reference;
  }
}

Vector3 multilateration_start(std::span<const Vector3> receivers,
                              std::span<const double> differences) {
  const Eigen::Index rows = static_cast<Eigen::Index>(differences.size());
  Eigen::Matrix<double, Eigen::Dynamic, 3> a(rows, 3);
  Eigen::VectorXd b(rows);
  Vector3 q = Vector3::Zero();  // relative to the reference receiver
  for (int round = 0; round < kStartRounds; ++round) {
    for (Eigen::Index i = 0; i < rows; ++i) {
      const Vector3 t = receivers[static_cast<std::size_t>(i) + 1] - receivers[0];
      const double d = differences[static_cast<std::size_t>(i)];
      a.row(i) << 2.0 * t.x(), 2.0 * t.y(), 2.0 * d;
      b(i) = t.squaredNorm() - d * d - 2.0 * t.z() * q.z();
    }
    const Vector3 solved = a.colPivHouseholderQr().solve(b);  // (q_x, q_y, r_0)
    q.x() = solved(0);
    q.y() = solved(1);
    const double r0 = solved(2);
    q.z() = std::sqrt(std::max(r0 * r0 - q.x() * q.x() - q.y() * q.y(), 0.0));
  }
  return receivers[0] + q;
}

namespace {

// The damped Gauss-Newton descent from `start`, no lower than `floor`.
MultilaterationFix descend(std::span<const Vector3> receivers, std::span<const double> differences,
                           std::span<const double> variances, const Vector3& start, double floor) {
  const std::size_t n = differences.size();
  std::vector<double> predicted(n);
  MultilaterationFix fix;
  fix.position = Vector3(start.x(), start.y(), std::max(start.z(), floor));
  fix.cost = weighted_cost(receivers, differences, variances, fix.position, predicted);
  double damping = kInitialDamping;
  for (; fix.iterations < kMaxIterations && !fix.converged; ++fix.iterations) {
    // The normal equations of the linearised weighted least squares at the current point.
    const Vector3 to_reference = fix.position - receivers[0];
    const double reference = to_reference.norm();
    Covariance<3> normal = Covariance<3>::Zero();
    Vector3 gradient = Vector3::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      const Vector3 to_receiver = fix.position - receivers[i + 1];
      const Vector3 row = to_receiver / to_receiver.norm() - to_reference / reference;
      normal += row * row.transpose() / variances[i];
      gradient += row * (differences[i] - predicted[i]) / variances[i];
    }
    if (!normal.allFinite()) break;
    // Levenberg-Marquardt: damp the step along each coordinate's own curvature until it
    // lowers the cost. The height is the weak coordinate of ground receivers; undamped
    // Gauss-Newton overshoots along that long, curved valley and crawls.
    for (; damping <= kMaxDamping; damping *= 10.0) {
      Covariance<3> damped = normal;
      damped.diagonal() *= 1.0 + damping;
      Vector3 step = damped.ldlt().solve(gradient);
      if (fix.position.z() <= floor && step.z() < 0.0) {
        // On the floor and pulled under it: the best step along it, the height held.
        step.z() = 0.0;
        step.head<2>() = damped.topLeftCorner<2, 2>().ldlt().solve(gradient.head<2>());
      }
      Vector3 candidate = fix.position + step;
      candidate.z() = std::max(candidate.z(), floor);
      const double cost = weighted_cost(receivers, differences, variances, candidate, predicted);
      if (step.allFinite() && cost <= fix.cost) {
        fix.converged = (candidate - fix.position).norm() < kStepToleranceM;
        fix.position = candidate;
        fix.cost = cost;
        damping = std::max(damping / 10.0, kMinDamping);
        break;
      }
    }
    // No damping lowered the cost: the current point is the minimum to within rounding.
    if (damping > kMaxDamping) fix.converged = true;
    range_differences(receivers, fix.position, predicted);
  }
  return fix;
}

}  // namespace

MultilaterationFix solve_multilateration(std::span<const Vector3> receivers,
                                         std::span<const double> differences,
                                         std::span<const double> variances) {
  assert(variances.size() == differences.size() && receivers.size() == differences.size() + 1);
  // Nothing flies under the lowest receiver: the fix is the minimum above it.
  double floor = receivers[0].z();
  for (const Vector3& s : receivers) floor = std::min(floor, s.z());
  // Ground receivers see an aircraft low over them and one high up almost alike: the cost can
  // have a minimum near the floor and another above, and noise decides which is lower. The
  // descent runs from the closed-form start and from its position at fixed heights above the
  // floor; the lowest cost wins.
  const Vector3 start = multilateration_start(receivers, differences);
  MultilaterationFix fix = descend(receivers, differences, variances, start, floor);
  for (const double height : kRestartHeightsM) {
    const Vector3 other_start(start.x(), start.y(), floor + height);
    const MultilaterationFix other = descend(receivers, differences, variances, other_start, floor);
    if (other.cost < fix.cost) fix = other;
  }
  return fix;
}

}  // namespace skyfuse
