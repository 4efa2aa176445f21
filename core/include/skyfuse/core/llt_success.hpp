#pragma once
/// \file
/// Whether an Eigen::LLT really factorised its matrix. Eigen tests each pivot with `x <= 0`,
/// which a NaN passes, and then reports Success with NaN in L; a NaN or Inf anywhere in the
/// lower triangle reaches L's diagonal, so a finite diagonal is the missing half of the test.

#include <Eigen/Cholesky>

namespace skyfuse {

template <typename MatrixType, int UpLo>
bool llt_succeeded(const Eigen::LLT<MatrixType, UpLo>& llt) {
  return llt.info() == Eigen::Success && llt.matrixLLT().diagonal().allFinite();
}

}  // namespace skyfuse
