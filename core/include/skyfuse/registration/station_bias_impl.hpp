#pragma once
/// \file
/// The definitions of StationBias's members (station_bias.hpp). Only the files that compile a
/// picture's code once per state size include it (picture/state_size_code.hpp) and the tests of
/// other sizes; every other file calls the compiled code.

#include <Eigen/Cholesky>
#include <stdexcept>
#include <variant>

#include "skyfuse/registration/station_bias.hpp"

namespace skyfuse {

template <int N>
auto StationBias<N>::prior_estimate(const Sensor& sensor, const SensorBias& prior_std) -> Estimate {
  return std::visit(
      [&]<typename S>(const S&) -> Estimate {
        const auto prior = BiasEstimate<S>::from_sensor_bias(prior_std);
        if (!(prior.minCoeff() > 0.0)) {
          throw std::invalid_argument("StationBias: every prior standard deviation must be > 0");
        }
        return BiasEstimate<S>(prior);
      },
      sensor);
}

template <int N>
void StationBias<N>::set_prior_covariance(const SensorBias& prior_std) {
  std::visit(
      [&]<typename S>(const BiasEstimate<S>&) {
        set_covariance(BiasEstimate<S>::from_sensor_bias(prior_std).cwiseAbs2().asDiagonal());
      },
      estimate_);
}

template <int N>
bool StationBias<N>::learn(const Sensor& sensor, const GaussianState<N>& prior, const Detection& z,
                           const DetectionNoise& noise, const ConsideredCross* absorbed) {
  return std::visit(
      [&]<typename S>(const S& typed) {
        constexpr int M = S::kMeasDim;
        constexpr int D = BiasEstimate<S>::kDim;
        auto& estimate = std::get<BiasEstimate<S>>(estimate_);
        if (absorbed == nullptr || absorbed->rows() != N || absorbed->cols() != D) {
          return estimate.add(typed, prior, fixed_detection<M>(z), fixed_noise<M>(noise));
        }
        const Matrix<N, D> cross = *absorbed;
        const Covariance<D> l = factor_.template topLeftCorner<D, D>();
        // A = H C̃ L⁻¹, from Lᵀ Aᵀ = (H C̃)ᵀ.
        const Matrix<M, D> a = l.transpose()
                                   .template triangularView<Eigen::Upper>()
                                   .solve((typed.jacobian(prior.mean) * cross).transpose())
                                   .transpose();
        GaussianState<N> rest{prior.mean, prior.covariance - cross * cross.transpose()};
        symmetrize(rest.covariance);
        // r = z − h(x̂) ≈ (G + A) b − A b̂ + …: the known part moved to z.
        const Vector<M> shifted =
            fixed_detection<M>(z) + a * BiasEstimate<S>::from_sensor_bias(bias_);
        return estimate.add(typed, rest, shifted, fixed_noise<M>(noise), a);
      },
      sensor);
}

template <int N>
bool StationBias<N>::settle() {
  return std::visit(
      [&]<typename S>(const BiasEstimate<S>& estimate) {
        constexpr int D = BiasEstimate<S>::kDim;
        // Until it settles, nothing moved and nothing narrowed.
        move_.setZero(D);
        narrowing_.setIdentity(D, D);
        const auto settled = estimate.estimate();
        if (!settled) return false;
        // How far the estimate moved, in the standardised errors of the one it replaces.
        // (Entry by entry, and solved in the dynamic vector: GCC 12 warns falsely of
        // -Warray-bounds on the packet arithmetic of a one-entry estimate's.)
        const Vector<D> before = BiasEstimate<S>::from_sensor_bias(bias_);
        for (int i = 0; i < D; ++i) move_(i) = settled->mean(i) - before(i);
        const auto old_factor = factor_.topLeftCorner(D, D).template triangularView<Eigen::Lower>();
        old_factor.solveInPlace(move_);
        bias_ = BiasEstimate<S>::as_sensor_bias(settled->mean);
        const decltype(factor_) replaced = factor_;
        set_covariance(settled->covariance);
        // L_old⁻¹ L_new: the new standardised errors in the old ones' units.
        narrowing_ = factor_;
        replaced.topLeftCorner(D, D).template triangularView<Eigen::Lower>().solveInPlace(
            narrowing_);
        return true;
      },
      estimate_);
}

template <int N>
SensorBias StationBias<N>::sigma() const {
  return std::visit(
      [&]<typename S>(const BiasEstimate<S>&) {
        return BiasEstimate<S>::as_sensor_bias(
            fixed_covariance<BiasEstimate<S>::kDim>().diagonal().cwiseSqrt());
      },
      estimate_);
}

template <int N>
std::array<bool, 4> StationBias<N>::estimated() const {
  return std::visit(
      [&]<typename S>(const BiasEstimate<S>&) {
        std::array<bool, 4> held{false, false, false, true};
        for (const int c : BiasEstimate<S>::kOffsetOf) {
          if (c >= 0) held[static_cast<std::size_t>(c)] = true;
        }
        return held;
      },
      estimate_);
}

template <int N>
template <typename S>
BiasCorrection<S> StationBias<N>::correction(const S& sensor, const Vector<N>& mean) const {
  constexpr int D = BiasEstimate<S>::kDim;
  BiasCorrection<S> c;
  c.g = BiasEstimate<S>::bias_jacobian(sensor.jacobian(mean), mean);
  c.b = BiasEstimate<S>::from_sensor_bias(bias_);
  c.noise = c.g * fixed_covariance<D>() * c.g.transpose();
  c.g_scaled = c.g * factor_.template topLeftCorner<D, D>();
  return c;
}

template <int N>
DetectionNoise StationBias<N>::correction_noise(const Sensor& sensor, const Vector<N>& mean) const {
  return std::visit(
      [&]<typename S>(const S& typed) -> DetectionNoise { return correction(typed, mean).noise; },
      sensor);
}

// E: which of sensor S's M measured values each of its D − 1 offsets (the biases but the
// clock) moves.
template <typename S>
Matrix<S::kMeasDim, BiasEstimate<S>::kDim - 1> offsets_selection() {
  constexpr int M = S::kMeasDim;
  Matrix<M, BiasEstimate<S>::kDim - 1> e = Matrix<M, BiasEstimate<S>::kDim - 1>::Zero();
  int column = 0;
  for (int i = 0; i < M; ++i) {
    if (BiasEstimate<S>::kOffsetOf[static_cast<std::size_t>(i)] >= 0) e(i, column++) = 1.0;
  }
  return e;
}

template <int N>
DetectionNoise StationBias<N>::offsets_noise(const Sensor& sensor) const {
  return std::visit(
      [&]<typename S>(const S&) -> DetectionNoise {
        constexpr int D = BiasEstimate<S>::kDim;
        const auto e = offsets_selection<S>();
        return e * fixed_covariance<D>().template topLeftCorner<D - 1, D - 1>() * e.transpose();
      },
      sensor);
}

template <int N>
ConsideredCross StationBias<N>::offsets_factor(const Sensor& sensor) const {
  return std::visit(
      [&]<typename S>(const S&) -> ConsideredCross {
        constexpr int M = S::kMeasDim;
        constexpr int D = BiasEstimate<S>::kDim;
        ConsideredCross e = ConsideredCross::Zero(M, D);  // the clock's column zero
        e.leftCols(D - 1) = offsets_selection<S>();
        return ConsideredCross(e * factor_.topLeftCorner(D, D));
      },
      sensor);
}

template <int N>
Detection StationBias<N>::corrected(const Sensor& sensor, const Detection& z,
                                    const Vector<N>& mean) const {
  return std::visit(
      [&]<typename S>(const S& typed) -> Detection {
        return correction(typed, mean).applied(fixed_detection<S::kMeasDim>(z));
      },
      sensor);
}

template <int N>
Detection StationBias<N>::offsets_removed(const Sensor& sensor, const Detection& z) const {
  return std::visit(
      [&]<typename S>(const S&) -> Detection {
        constexpr int M = S::kMeasDim;
        return S::to_reported(fixed_detection<M>(z) - offsets_of<S>(bias_));
      },
      sensor);
}

template <int N>
BiasSums StationBias<N>::sums(int station_id) const {
  return std::visit(
      [&]<typename S>(const BiasEstimate<S>& estimate) {
        return BiasSums{station_id, estimate.information(), estimate.information_vector(),
                        estimate.detections()};
      },
      estimate_);
}

template <int N>
bool StationBias<N>::restore(const BiasSums& sums) {
  return std::visit(
      [&]<typename S>(BiasEstimate<S>& estimate) {
        constexpr int D = BiasEstimate<S>::kDim;
        if (sums.information.rows() != D || sums.information.cols() != D ||
            sums.information_vector.size() != D) {
          return false;
        }
        const BiasEstimate<S> before = estimate;
        estimate.restore(sums.information, sums.information_vector,
                         static_cast<std::size_t>(sums.detections));
        if (settle()) return true;
        estimate = before;
        return false;
      },
      estimate_);
}

template <int N>
template <typename Cov>
void StationBias<N>::set_covariance(const Cov& covariance) {
  covariance_ = covariance;
  factor_ = covariance_.llt().matrixL();
}

}  // namespace skyfuse
