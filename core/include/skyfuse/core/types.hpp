#pragma once
/// \file
/// Dimension-typed Eigen aliases shared by every model and filter.
///
/// A state of dimension N and a measurement of dimension M are fixed at compile time, so a
/// mismatched Jacobian or gain is a compile error rather than a run-time surprise. Dynamic sizes
/// appear only where the number of stations enters (the stacked EKF).

#include <Eigen/Core>

namespace skyfuse {

template <int N>
using Vector = Eigen::Matrix<double, N, 1>;

template <int Rows, int Cols>
using Matrix = Eigen::Matrix<double, Rows, Cols>;

template <int N>
using Covariance = Eigen::Matrix<double, N, N>;

/// Maps a state of dimension N to a measurement of dimension M: dh/dx is M x N.
template <int M, int N>
using Jacobian = Eigen::Matrix<double, M, N>;

using Vector3 = Vector<3>;
using Matrix3 = Matrix<3, 3>;

/// A Gaussian belief over a state whose dimension is known only at run time: what the harness
/// records of a run of any motion model.
struct DynamicGaussianState {
  Eigen::VectorXd mean;
  Eigen::MatrixXd covariance;
};

/// Mean and covariance of a Gaussian belief over a state of dimension N.
template <int N>
struct GaussianState {
  static constexpr int kDim = N;
  Vector<N> mean = Vector<N>::Zero();
  Covariance<N> covariance = Covariance<N>::Identity();
};

/// Forces exact symmetry; rounding in P = A P A^T leaves the two triangles a few ulps apart.
/// Each off-diagonal pair becomes its mean (the same bits as 0.5 (m + m^T)).
template <typename Derived>
void symmetrize(Eigen::MatrixBase<Derived>& m) {
  for (Eigen::Index c = 1; c < m.cols(); ++c) {
    for (Eigen::Index r = 0; r < c; ++r) {
      const double mean = 0.5 * (m(r, c) + m(c, r));
      m(r, c) = mean;
      m(c, r) = mean;
    }
  }
}

/// How many leading state components a sensor's measurement depends on: dh/dx is zero beyond
/// them. Sensors that declare kJacobianCols (the 3-D position sensors: 3) let the filters
/// work on that block only; others use the whole state.
template <typename Sensor>
constexpr int jacobian_cols() {
  if constexpr (requires { Sensor::kJacobianCols; }) {
    return Sensor::kJacobianCols;
  } else {
    return Sensor::kStateDim;
  }
}

}  // namespace skyfuse
