#include "skyfuse/picture/track_merge.hpp"

#include <Eigen/Cholesky>
#include <limits>

namespace skyfuse {

double merge_distance(const Vector<kMergeDim>& difference, const Covariance<kMergeDim>& spread) {
  const Eigen::LLT<Covariance<kMergeDim>> factor(spread);
  if (factor.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  return difference.dot(factor.solve(difference));
}

}  // namespace skyfuse
