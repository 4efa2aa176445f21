#pragma once
/// \file
/// One station's biases estimated from its detections of tracked aircraft (docs/registration.md):
/// the offsets of the components its sensor measures that a bias reaches (range, azimuth,
/// elevation: traffic/sensor_bias.hpp) and its clock, as a linear least-squares problem in
/// information form, so that sums made in the same order are the same bits.
///
/// A detection z of an aircraft whose track's prior is N(x̂, P) gives the residual
///
///   r = z - h(x̂) ≈ G b + H (x - x̂) + ν,    G = [E, H_p v̂],    S = H P Hᵀ + R,
///
/// with E the unit columns of the offset components, H_p the Jacobian's position columns and v̂
/// the prior's velocity (a clock late by τ sees the aircraft τ v further on). Each adds GᵀS⁻¹G
/// to the information and GᵀS⁻¹r to its vector; with the prior's information Λ0,
///
///   b̂ = (Λ0 + Σ GᵀS⁻¹G)⁻¹ Σ GᵀS⁻¹r.
///
/// The track's error x - x̂ is taken as noise independent of b; where the track is the
/// aircraft's own broadcast it is (an absolute reference), where other biased stations made it
/// the estimate is relative to theirs.

#include <array>
#include <cstddef>
#include <optional>

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/traffic/sensor_bias.hpp"

namespace skyfuse {

/// How many of `Sensor`'s components a bias offsets (SensorBias::kComponents).
template <typename Sensor>
constexpr int offset_components() {
  int count = 0;
  for (const int c : bias_components_of<Sensor>()) count += c < 0 ? 0 : 1;
  return count;
}

template <typename Sensor>
class BiasEstimate {
 public:
  static constexpr int kMeasDim = Sensor::kMeasDim;
  /// The offsets, in the sensor's component order, then the clock.
  static constexpr int kDim = offset_components<Sensor>() + 1;
  using Bias = Vector<kDim>;
  /// Which bias offset reaches each measured component (-1: none).
  static constexpr auto kOffsetOf = bias_components_of<Sensor>();

  /// No detection yet: the prior, b ~ N(0, diag(prior_std²)), one standard deviation per
  /// entry in the order above.
  explicit BiasEstimate(const Bias& prior_std) {
    information_.setZero();
    information_.diagonal() = prior_std.cwiseInverse().cwiseAbs2();
    information_vector_.setZero();
  }

  /// Adds detection `z` (noise `noise`) of the aircraft whose track has prior `prior`. False,
  /// and nothing added, where S does not factor.
  /// `absorbed`: what of the biases the track's error itself holds, E[H (x − x̂) | b] per unit
  /// of b (a track correlated with them, registration/considered_biases.hpp), added to ∂r/∂b.
  template <int N>
  bool add(const Sensor& sensor, const GaussianState<N>& prior, const Vector<kMeasDim>& z,
           const Covariance<kMeasDim>& noise,
           const Matrix<kMeasDim, kDim>& absorbed = Matrix<kMeasDim, kDim>::Zero()) {
    const Jacobian<kMeasDim, N> h = sensor.jacobian(prior.mean);
    const Vector<kMeasDim> r = sensor.residual(z, sensor.predict(prior.mean));
    const Matrix<kMeasDim, kDim> g = bias_jacobian(h, prior.mean) + absorbed;
    Covariance<kMeasDim> s = h * prior.covariance * h.transpose() + noise;
    symmetrize(s);
    SmallCholesky<kMeasDim> factor;
    if (!factor.compute(s)) return false;
    Matrix<kMeasDim, kDim> s_inv_g;
    for (int c = 0; c < kDim; ++c) s_inv_g.col(c) = factor.solve(g.col(c));
    information_ += g.transpose() * s_inv_g;
    symmetrize(information_);
    information_vector_ += s_inv_g.transpose() * r;
    ++detections_;
    return true;
  }

  /// ∂r/∂b at the prior's mean: the offsets' unit columns, then H_p v̂ for the clock.
  template <int N>
  static Matrix<kMeasDim, kDim> bias_jacobian(const Jacobian<kMeasDim, N>& h,
                                              const Vector<N>& mean) {
    Matrix<kMeasDim, kDim> g = Matrix<kMeasDim, kDim>::Zero();
    int column = 0;
    for (int i = 0; i < kMeasDim; ++i) {
      if (kOffsetOf[static_cast<std::size_t>(i)] >= 0) g(i, column++) = 1.0;
    }
    g.col(kDim - 1) = h.template leftCols<3>() * mean.template segment<3>(3);
    return g;
  }

  /// b̂ and its covariance; none where the information does not factor.
  std::optional<GaussianState<kDim>> estimate() const {
    SmallCholesky<kDim> factor;
    if (!factor.compute(information_)) return std::nullopt;
    return GaussianState<kDim>{factor.solve(information_vector_), factor.inverse()};
  }

  /// The entries of `bias` this sensor's estimate keeps, in its order (e.g. a prior's standard
  /// deviations given by name).
  static Bias from_sensor_bias(const SensorBias& bias) {
    Bias b;
    int column = 0;
    for (const int c : kOffsetOf) {
      if (c >= 0) b(column++) = bias.offset(static_cast<std::size_t>(c));
    }
    b(kDim - 1) = bias.time_s;
    return b;
  }

  /// The bias as the scenario names it (offsets the sensor does not measure stay 0).
  static SensorBias as_sensor_bias(const Bias& b) {
    SensorBias bias;
    int column = 0;
    for (const int c : kOffsetOf) {
      if (c >= 0) bias.set_offset(static_cast<std::size_t>(c), b(column++));
    }
    bias.time_s = b(kDim - 1);
    return bias;
  }

  /// Takes another node's sums as this estimate's (StationBias::restore): the same sums, the
  /// same estimate bit for bit.
  void restore(const Covariance<kDim>& information, const Bias& information_vector,
               std::size_t detections) {
    information_ = information;
    information_vector_ = information_vector;
    detections_ = detections;
  }

  const Covariance<kDim>& information() const { return information_; }
  const Bias& information_vector() const { return information_vector_; }
  std::size_t detections() const { return detections_; }

 private:
  Covariance<kDim> information_;
  Bias information_vector_;
  std::size_t detections_ = 0;
};

}  // namespace skyfuse
