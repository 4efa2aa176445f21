#pragma once
/// \file
/// One station's registration, for whichever of a picture's sensors it has
/// (picture/picture_sensor.hpp): its BiasEstimate, what it learns from a detection of a tracked
/// aircraft, and its detections corrected by the current estimate. The estimate moves only
/// when settle() is called (once a round), so that every detection of a round is corrected
/// alike whatever the order it is met in.

#include <Eigen/Cholesky>
#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <variant>

#include "skyfuse/picture/picture_sensor.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/registration/bias_estimate.hpp"
#include "skyfuse/registration/considered_biases.hpp"

namespace skyfuse {

namespace detail {
template <typename Sensors>
struct BiasEstimateOf;
template <typename... S>
struct BiasEstimateOf<std::variant<S...>> {
  using type = std::variant<BiasEstimate<S>...>;
};
}  // namespace detail

/// What a station's registration has summed — its estimate's information, information vector
/// and detections — which is all another node needs to hold the same estimate bit for bit (a
/// restarted station, a peer that missed a scan: transport/picture_wire.hpp).
struct BiasSums {
  using Information = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 4, 4>;
  using InformationVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 4, 1>;

  int station_id = 0;
  Information information;
  InformationVector information_vector;
  std::uint64_t detections = 0;
};

/// A station's correction of its detections of one track, of sensor S: G(x̂), the Jacobian
/// of the detection in the biases at the track's prior mean, the settled biases b̂, and what the
/// registration does not know yet, G Σ Gᵀ. Added to R, that noise makes the gates and updates
/// consider the biases not yet known (a Schmidt, or "consider", treatment: the biases are not
/// states of the tracks, but their uncertainty is not ignored either).
template <typename S>
struct BiasCorrection {
  static constexpr int M = S::kMeasDim;
  static constexpr int D = BiasEstimate<S>::kDim;

  Matrix<M, D> g;
  Vector<D> b;
  Covariance<M> noise;
  /// G L, Σ = L Lᵀ: the Jacobian in the biases' standardised errors, which a track that keeps
  /// its cross-covariance with them takes instead of the noise (registration/
  /// considered_biases.hpp).
  Matrix<M, D> g_scaled;

  /// z − G b̂, as the sensor reports it (angles wrapped).
  Vector<M> applied(const Vector<M>& z) const { return S::to_reported(z - g * b); }
};

template <int N>
class StationBias {
 public:
  using Sensor = PictureSensor<N>;
  using Estimate = typename detail::BiasEstimateOf<Sensor>::type;

  /// A station of `sensor` whose biases are a priori N(0, prior_std²), each entry > 0
  /// (prior_std names them as a scenario's `bias:` does; entries the sensor does not measure
  /// are not read).
  StationBias(const Sensor& sensor, const SensorBias& prior_std)
      : estimate_(std::visit(
            [&]<typename S>(const S&) -> Estimate {
              const auto prior = BiasEstimate<S>::from_sensor_bias(prior_std);
              if (!(prior.minCoeff() > 0.0)) {
                throw std::invalid_argument(
                    "StationBias: every prior standard deviation must be > 0");
              }
              return BiasEstimate<S>(prior);
            },
            sensor)) {
    // Until the first settle the corrections are zero and as uncertain as the prior.
    std::visit(
        [&]<typename S>(const BiasEstimate<S>&) {
          set_covariance(BiasEstimate<S>::from_sensor_bias(prior_std).cwiseAbs2().asDiagonal());
        },
        estimate_);
  }

  /// Adds detection `z` (noise `noise`) of the aircraft whose track has prior `prior`: z as
  /// the station measured it, biases and all. False, and nothing added, where S does not
  /// factor.
  ///
  /// `absorbed`, where the track keeps its cross-covariance C̃ with this station's bias error
  /// (registration/considered_biases.hpp): its error is then partly this station's bias, which
  /// the detection's residual does not show — E[x − x̂ | b] = C̃ L⁻¹ (b − b̂) — so the detection
  /// teaches the biases through H (C̃ L⁻¹) beside G, against the track's error without that
  /// part, P − C̃ C̃ᵀ.
  bool learn(const Sensor& sensor, const GaussianState<N>& prior, const Detection& z,
             const DetectionNoise& noise, const ConsideredCross* absorbed = nullptr) {
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

  /// Takes what was learnt into the estimate the corrections use; false, and the estimate as
  /// it was, where the information does not factor.
  bool settle() {
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
          const auto old_factor =
              factor_.topLeftCorner(D, D).template triangularView<Eigen::Lower>();
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

  /// The biases the corrections use (none learnt: zero).
  const SensorBias& bias() const { return bias_; }

  /// How far the last settle() moved them, in the standardised errors u of the estimate it
  /// replaced (L⁻¹ (b̂_new − b̂_old)): what a track that keeps its cross-covariance C̃ with them
  /// expects its own error to have been, C̃ u (registration/considered_biases.hpp).
  const Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 4, 1>& last_move() const {
    return move_;
  }
  /// How the last settle() narrowed them: A = L_old⁻¹ L_new, so that u_old = last_move() +
  /// A u_new, and what is still unknown of u_old is A Aᵀ (the identity where nothing settled).
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 4, 4>&
  last_narrowing() const {
    return narrowing_;
  }

  /// Their standard deviations, as settled (before the first settle: the prior's); 0 for an
  /// entry the sensor's estimate does not hold (estimated()).
  SensorBias sigma() const {
    return std::visit(
        [&]<typename S>(const BiasEstimate<S>&) {
          return BiasEstimate<S>::as_sensor_bias(
              fixed_covariance<BiasEstimate<S>::kDim>().diagonal().cwiseSqrt());
        },
        estimate_);
  }

  /// Which of SensorBias's entries (range, azimuth, elevation, clock) the estimate holds.
  std::array<bool, 4> estimated() const {
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

  /// Station sensor `sensor`'s correction for the track of prior mean `mean` (BiasCorrection),
  /// for a caller that knows the sensor's type: G computed once for every detection of the
  /// track and for its noise.
  template <typename S>
  BiasCorrection<S> correction(const S& sensor, const Vector<N>& mean) const {
    constexpr int D = BiasEstimate<S>::kDim;
    BiasCorrection<S> c;
    c.g = BiasEstimate<S>::bias_jacobian(sensor.jacobian(mean), mean);
    c.b = BiasEstimate<S>::from_sensor_bias(bias_);
    c.noise = c.g * fixed_covariance<D>() * c.g.transpose();
    c.g_scaled = c.g * factor_.template topLeftCorner<D, D>();
    return c;
  }

  /// How uncertain a detection corrected for the track of prior mean `mean` still is: G Σ Gᵀ
  /// (BiasCorrection::noise).
  DetectionNoise correction_noise(const Sensor& sensor, const Vector<N>& mean) const {
    return std::visit(
        [&]<typename S>(const S& typed) -> DetectionNoise { return correction(typed, mean).noise; },
        sensor);
  }

  /// The same for the offsets alone, E Σ Eᵀ: what a detection no track has met still carries
  /// (its clock's part needs a velocity; clock_variance() gives it to whoever has one).
  DetectionNoise offsets_noise(const Sensor& sensor) const {
    return std::visit(
        [&]<typename S>(const S&) -> DetectionNoise {
          constexpr int M = S::kMeasDim;
          constexpr int D = BiasEstimate<S>::kDim;
          Matrix<M, D - 1> e = Matrix<M, D - 1>::Zero();
          int column = 0;
          for (int i = 0; i < M; ++i) {
            if (BiasEstimate<S>::kOffsetOf[static_cast<std::size_t>(i)] >= 0) e(i, column++) = 1.0;
          }
          return e * fixed_covariance<D>().template topLeftCorner<D - 1, D - 1>() * e.transpose();
        },
        sensor);
  }

  /// The offsets' part of the standardised errors: E L (M × D, the clock's column zero), so that
  /// a detection no track has met, its offsets removed, still carries E L u (u = L⁻¹ (b − b̂)).
  ConsideredCross offsets_factor(const Sensor& sensor) const {
    return std::visit(
        [&]<typename S>(const S&) -> ConsideredCross {
          constexpr int M = S::kMeasDim;
          constexpr int D = BiasEstimate<S>::kDim;
          ConsideredCross e = ConsideredCross::Zero(M, D);
          int column = 0;
          for (int i = 0; i < M; ++i) {
            if (BiasEstimate<S>::kOffsetOf[static_cast<std::size_t>(i)] >= 0) e(i, column++) = 1.0;
          }
          return ConsideredCross(e * factor_.topLeftCorner(D, D));
        },
        sensor);
  }

  /// The settled variance of the clock offset (s²).
  double clock_variance() const {
    return covariance_(covariance_.rows() - 1, covariance_.cols() - 1);
  }

  /// `z` corrected for the aircraft whose track's prior mean is `mean`: z − G(x̂) b̂, the
  /// clock's part included (BiasCorrection::applied).
  Detection corrected(const Sensor& sensor, const Detection& z, const Vector<N>& mean) const {
    return std::visit(
        [&]<typename S>(const S& typed) -> Detection {
          return correction(typed, mean).applied(fixed_detection<S::kMeasDim>(z));
        },
        sensor);
  }

  /// `z` corrected by the offsets alone, for a detection no track has met (initiation): the
  /// clock's part needs the aircraft's velocity.
  Detection offsets_removed(const Sensor& sensor, const Detection& z) const {
    return std::visit(
        [&]<typename S>(const S&) -> Detection {
          constexpr int M = S::kMeasDim;
          return S::to_reported(fixed_detection<M>(z) - offsets_of<S>(bias_));
        },
        sensor);
  }

  const Estimate& estimate() const { return estimate_; }

  /// What it has summed, for station `station_id` (BiasSums).
  BiasSums sums(int station_id) const {
    return std::visit(
        [&]<typename S>(const BiasEstimate<S>& estimate) {
          return BiasSums{station_id, estimate.information(), estimate.information_vector(),
                          estimate.detections()};
        },
        estimate_);
  }

  /// Takes `sums` (another node's, of a station of this sensor) as its own and settles them;
  /// false, and nothing changed, where they are not of this sensor's size or do not factor.
  bool restore(const BiasSums& sums) {
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

 private:
  template <int D>
  Covariance<D> fixed_covariance() const {
    return covariance_.template topLeftCorner<D, D>();
  }

  // Σ, and its lower Cholesky factor L for BiasCorrection::g_scaled (Σ is positive definite: a
  // prior of positive entries, or a settled estimate, which factored).
  template <typename Cov>
  void set_covariance(const Cov& covariance) {
    covariance_ = covariance;
    factor_ = covariance_.llt().matrixL();
  }

  Estimate estimate_;
  SensorBias bias_;
  /// Σ of the settled estimate, of its size (at most the three offsets and the clock).
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 4, 4> covariance_;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 4, 4> factor_;
  Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 4, 1> move_;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 4, 4> narrowing_;
};

}  // namespace skyfuse
