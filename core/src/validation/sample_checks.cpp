#include "skyfuse/validation/sample_checks.hpp"

#include <Eigen/Eigenvalues>

namespace skyfuse::detail {

std::optional<DropKind> check_eigenvalues(const BoundedSymmetric& scaled) {
  const Eigen::SelfAdjointEigenSolver<BoundedSymmetric> eigen(scaled, Eigen::EigenvaluesOnly);
  if (eigen.info() != Eigen::Success) return DropKind::kNotPositive;
  const double smallest = eigen.eigenvalues().minCoeff();
  const double scale = eigen.eigenvalues().cwiseAbs().maxCoeff();
  if (smallest < -1e-9 * scale) return DropKind::kNotPositive;
  return std::nullopt;
}

}  // namespace skyfuse::detail
