#pragma once
/// \file
/// The unscented information filter's measurement step, in the form the station network sums.
///
/// Sigma points of the common prior (x^, P), the scaled symmetric set with
/// lambda = alpha^2 (N + kappa) - N:
///
///   chi_0 = x^,   chi_j = x^ + sqrt(N + lambda) L e_j,   chi_{N+j} = x^ - sqrt(N + lambda) L e_j
///   Wm_0 = lambda / (N + lambda),  Wc_0 = Wm_0 + 1 - alpha^2 + beta,  W_j = 1 / (2 (N + lambda))
///
/// with P = L L^T. Station i pushes them through its sensor, z^_i = sum Wm_j h_i(chi_j) and
/// P_xz,i = sum Wc_j (chi_j - x^)(h_i(chi_j) - z^_i)^T, and regresses h_i on the state:
///
///   H~_i = (P^-1 P_xz,i)^T,   nu_i = z_i - z^_i (angles wrapped),
///   dQ_i = H~_i^T R_i^-1 H~_i,   dy_i = H~_i^T R_i^-1 (nu_i + H~_i x^).
///
/// These have the EKF increment's form with H~_i for H_i, so peers sum them exactly as the EKF's
/// (fusion/increment_fusion.hpp), and the center's update on the stacked measurement, whose
/// regression is the stack of the H~_i, is their sum. For a linear sensor H~_i = H_i and the
/// increment is the EKF's.

#include <Eigen/Cholesky>
#include <array>
#include <cmath>
#include <optional>

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/core/status.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/fusion/information_increment.hpp"

namespace skyfuse {

/// The sigma points' spread (alpha), prior knowledge of the distribution (beta: 2 for a
/// Gaussian) and secondary scaling (kappa). alpha = 1, kappa = 0 puts the points at sqrt(N)
/// standard deviations with a zero centre weight.
struct UnscentedParameters {
  double alpha = 1.0;
  double beta = 2.0;
  double kappa = 0.0;
};

/// The 2N + 1 sigma points of a prior and the factor of its covariance, computed once per round
/// and shared by every sensor that linearises about that prior.
template <int N>
class SigmaPoints {
 public:
  static constexpr int kCount = 2 * N + 1;

  /// False, and nothing usable, if P is not positive definite.
  bool compute(const GaussianState<N>& prior, const UnscentedParameters& p) {
    const auto& factor = factor_.emplace(prior.covariance);
    if (factor.info() != Eigen::Success) return false;
    const double lambda = p.alpha * p.alpha * (N + p.kappa) - N;
    const double spread = std::sqrt(N + lambda);
    const Covariance<N> l = factor.matrixL();
    points_[0] = prior.mean;
    for (int j = 0; j < N; ++j) {
      points_[1 + j] = prior.mean + spread * l.col(j);
      points_[1 + N + j] = prior.mean - spread * l.col(j);
    }
    mean_weight_0_ = lambda / (N + lambda);
    covariance_weight_0_ = mean_weight_0_ + 1.0 - p.alpha * p.alpha + p.beta;
    weight_ = 1.0 / (2.0 * (N + lambda));
    return true;
  }

  const Vector<N>& point(int j) const { return points_[static_cast<std::size_t>(j)]; }
  /// The prior's mean: the centre point.
  const Vector<N>& mean() const { return points_[0]; }
  double mean_weight(int j) const { return j == 0 ? mean_weight_0_ : weight_; }
  double covariance_weight(int j) const { return j == 0 ? covariance_weight_0_ : weight_; }
  /// The Cholesky factor of the prior's P, for P^-1 P_xz.
  const Eigen::LLT<Covariance<N>>& prior_factor() const { return *factor_; }

 private:
  // None before the first compute(): Eigen 3.4's default LLT leaves its norm and status unset,
  // and copying points never computed (a filter is moved into its node before its first round)
  // would copy those unset values (GCC's -Wmaybe-uninitialized said so). Factorising the identity
  // up front instead cost the unscented station step 6-12 %: a RoundPrior is made for every
  // station's step.
  std::optional<Eigen::LLT<Covariance<N>>> factor_;
  std::array<Vector<N>, kCount> points_{};
  double mean_weight_0_ = 0.0;
  double covariance_weight_0_ = 0.0;
  double weight_ = 0.0;
};

/// A sensor's statistical linearisation about the sigma points' prior: the predicted
/// measurement z^, the regression H~ = (P^-1 P_xz)^T and, when asked for (a NIS gate needs
/// it), the spread P_zz = sum Wc_j (h(chi_j) - z^)(h(chi_j) - z^)^T.
template <int M, int N>
struct StatisticalLinearisation {
  Vector<M> predicted = Vector<M>::Zero();
  Covariance<M> predicted_covariance = Covariance<M>::Zero();
  Matrix<M, N> regression = Matrix<M, N>::Zero();
};

/// Whether linearise() also forms P_zz: M x M more per sigma point, needed only to screen with
/// a NIS gate (formed always, inside the P_xz loop, a radar station's unscented step measured
/// 1.98-2.00 us against 1.72-1.79 us without).
enum class Spread { kLeaveOut, kForm };

/// Each sigma point's predicted measurement h(chi_j), taken relative to the centre point's
/// through the sensor's residual so that angles near +-pi average where they lie, and their
/// weighted mean z^. What the information form (linearise()) and the covariance form
/// (unscented_covariance_update.hpp) both start from.
template <int M, int N>
struct SigmaPredictions {
  std::array<Vector<M>, SigmaPoints<N>::kCount> points;
  Vector<M> mean = Vector<M>::Zero();
};

template <int N, typename Sensor>
SigmaPredictions<Sensor::kMeasDim, N> predict_sigma_points(const SigmaPoints<N>& sigma,
                                                           const Sensor& sensor) {
  SigmaPredictions<Sensor::kMeasDim, N> out;
  const Vector<Sensor::kMeasDim> centre = sensor.predict(sigma.point(0));
  for (int j = 0; j < SigmaPoints<N>::kCount; ++j) {
    const auto i = static_cast<std::size_t>(j);
    out.points[i] = centre + Sensor::residual(sensor.predict(sigma.point(j)), centre);
    out.mean += sigma.mean_weight(j) * out.points[i];
  }
  return out;
}

/// z^ and H~ of `sensor` over `sigma` (and P_zz with Spread::kForm).
template <int N, typename Sensor>
StatisticalLinearisation<Sensor::kMeasDim, N> linearise(const SigmaPoints<N>& sigma,
                                                        const Sensor& sensor,
                                                        Spread spread_too = Spread::kLeaveOut) {
  constexpr int M = Sensor::kMeasDim;
  const SigmaPredictions<M, N> predictions = predict_sigma_points(sigma, sensor);
  const auto& z = predictions.points;
  StatisticalLinearisation<M, N> out;
  out.predicted = predictions.mean;
  Matrix<N, M> cross = Matrix<N, M>::Zero();  // P_xz
  for (int j = 0; j < SigmaPoints<N>::kCount; ++j) {
    cross += sigma.covariance_weight(j) * (sigma.point(j) - sigma.mean()) *
             (z[static_cast<std::size_t>(j)] - out.predicted).transpose();
  }
  if (spread_too == Spread::kForm) {  // a loop of its own: the one above stays as tight
    for (int j = 0; j < SigmaPoints<N>::kCount; ++j) {
      const Vector<M> spread = z[static_cast<std::size_t>(j)] - out.predicted;
      out.predicted_covariance += sigma.covariance_weight(j) * spread * spread.transpose();
    }
  }
  out.regression = sigma.prior_factor().solve(cross).transpose();
  return out;
}

/// The unscented innovation's NIS, nu^T (P_zz + R)^-1 nu, of measurement z (noise R) against
/// `lin` (linearised with Spread::kForm); nothing if P_zz + R is not positive definite. What the
/// NIS gate screens with.
template <int M, int N, typename Sensor>
std::optional<double> unscented_nis(const StatisticalLinearisation<M, N>& lin, const Sensor&,
                                    const Vector<M>& z, const Covariance<M>& noise) {
  SmallCholesky<M> s_factor;
  if (!s_factor.compute(lin.predicted_covariance + noise)) return std::nullopt;
  const Vector<M> innovation = Sensor::residual(z, lin.predicted);
  return innovation.dot(s_factor.solve(innovation));
}

/// Station `station_id`'s unscented information increment for measurement z (noise R) against
/// the prior of `sigma`, linearised as `lin`, into `out`. Fails only if R is not positive
/// definite.
template <int N, typename Sensor>
NumericalStatus compute_unscented_increment(
    int station_id, const SigmaPoints<N>& sigma,
    const StatisticalLinearisation<Sensor::kMeasDim, N>& lin, const Vector<Sensor::kMeasDim>& z,
    const Covariance<Sensor::kMeasDim>& noise, InformationIncrement<N>& out) {
  constexpr int M = Sensor::kMeasDim;
  SmallCholesky<M> r_factor;
  if (!r_factor.compute(noise)) return NumericalStatus::kNotPositiveDefinite;
  const Vector<M> innovation = Sensor::residual(z, lin.predicted);
  Matrix<M, N> r_inv_h;  // R^-1 H~
  for (int c = 0; c < N; ++c) r_inv_h.col(c) = r_factor.solve(lin.regression.col(c));
  out.station_id = station_id;
  out.delta_information = lin.regression.transpose().lazyProduct(r_inv_h);
  symmetrize(out.delta_information);
  out.delta_vector = r_inv_h.transpose() * (innovation + lin.regression * sigma.mean());
  return NumericalStatus::kOk;
}

/// The same, linearising `sensor` over `sigma` first.
template <int N, typename Sensor>
NumericalStatus compute_unscented_increment(int station_id, const SigmaPoints<N>& sigma,
                                            const Sensor& sensor, const Vector<Sensor::kMeasDim>& z,
                                            const Covariance<Sensor::kMeasDim>& noise,
                                            InformationIncrement<N>& out) {
  return compute_unscented_increment<N, Sensor>(station_id, sigma, linearise(sigma, sensor), z,
                                                noise, out);
}

}  // namespace skyfuse
