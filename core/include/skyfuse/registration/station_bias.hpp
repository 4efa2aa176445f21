#pragma once
/// \file
/// One station's registration, for whichever of a picture's sensors it has
/// (picture/picture_sensor.hpp): its BiasEstimate, what it learns from a detection of a tracked
/// aircraft, and its detections corrected by the current estimate. The estimate moves only
/// when settle() is called (once a round), so that every detection of a round is corrected
/// alike whatever the order it is met in.
///
/// Its members are defined in station_bias_impl.hpp and compiled once per state size with the
/// rest of what a picture's size alone decides (picture/state_size_code.hpp); this header
/// declares them.

#include <array>
#include <cstdint>
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
struct StateSizeCode;

template <int N>
class StationBias {
 public:
  using Sensor = PictureSensor<N>;
  using Estimate = typename detail::BiasEstimateOf<Sensor>::type;
  using Offsets = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 4, 1>;
  using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 4, 4>;

  /// A station of `sensor` whose biases are a priori N(0, prior_std²), each entry > 0
  /// (prior_std names them as a scenario's `bias:` does; entries the sensor does not measure
  /// are not read).
  StationBias(const Sensor& sensor, const SensorBias& prior_std)
      : estimate_(prior_estimate(sensor, prior_std)) {
    // Until the first settle the corrections are zero and as uncertain as the prior.
    set_prior_covariance(prior_std);
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
             const DetectionNoise& noise, const ConsideredCross* absorbed = nullptr);

  /// Takes what was learnt into the estimate the corrections use; false, and the estimate as
  /// it was, where the information does not factor.
  bool settle();

  /// The biases the corrections use (none learnt: zero).
  const SensorBias& bias() const { return bias_; }

  /// How far the last settle() moved them, in the standardised errors u of the estimate it
  /// replaced (L⁻¹ (b̂_new − b̂_old)): what a track that keeps its cross-covariance C̃ with them
  /// expects its own error to have been, C̃ u (registration/considered_biases.hpp).
  const Offsets& last_move() const { return move_; }
  /// How the last settle() narrowed them: A = L_old⁻¹ L_new, so that u_old = last_move() +
  /// A u_new, and what is still unknown of u_old is A Aᵀ (the identity where nothing settled).
  const Square& last_narrowing() const { return narrowing_; }

  /// Their standard deviations, as settled (before the first settle: the prior's); 0 for an
  /// entry the sensor's estimate does not hold (estimated()).
  SensorBias sigma() const;

  /// Which of SensorBias's entries (range, azimuth, elevation, clock) the estimate holds.
  std::array<bool, 4> estimated() const;

  /// Station sensor `sensor`'s correction for the track of prior mean `mean` (BiasCorrection),
  /// for a caller that knows the sensor's type: G computed once for every detection of the
  /// track and for its noise. Compiled for every sensor of the picture with the rest
  /// (station_bias_impl.hpp).
  template <typename S>
  BiasCorrection<S> correction(const S& sensor, const Vector<N>& mean) const;

  /// How uncertain a detection corrected for the track of prior mean `mean` still is: G Σ Gᵀ
  /// (BiasCorrection::noise).
  DetectionNoise correction_noise(const Sensor& sensor, const Vector<N>& mean) const;

  /// The same for the offsets alone, E Σ Eᵀ: what a detection no track has met still carries
  /// (its clock's part needs a velocity; clock_variance() gives it to whoever has one).
  DetectionNoise offsets_noise(const Sensor& sensor) const;

  /// The offsets' part of the standardised errors: E L (M × D, the clock's column zero), so that
  /// a detection no track has met, its offsets removed, still carries E L u (u = L⁻¹ (b − b̂)).
  ConsideredCross offsets_factor(const Sensor& sensor) const;

  /// The settled variance of the clock offset (s²).
  double clock_variance() const {
    return covariance_(covariance_.rows() - 1, covariance_.cols() - 1);
  }

  /// `z` corrected for the aircraft whose track's prior mean is `mean`: z − G(x̂) b̂, the
  /// clock's part included (BiasCorrection::applied).
  Detection corrected(const Sensor& sensor, const Detection& z, const Vector<N>& mean) const;

  /// `z` corrected by the offsets alone, for a detection no track has met (initiation): the
  /// clock's part needs the aircraft's velocity.
  Detection offsets_removed(const Sensor& sensor, const Detection& z) const;

  const Estimate& estimate() const { return estimate_; }

  /// What it has summed, for station `station_id` (BiasSums).
  BiasSums sums(int station_id) const;

  /// Takes `sums` (another node's, of a station of this sensor) as its own and settles them;
  /// false, and nothing changed, where they are not of this sensor's size or do not factor.
  bool restore(const BiasSums& sums);

 private:
  friend struct StateSizeCode<N>;  // which compiles the members below for its size

  // The constructor's work, out of line (a constructor cannot be kept by its address:
  // picture/state_size_code.hpp): the estimate of `sensor`'s biases at `prior_std`, and Σ at it.
  static Estimate prior_estimate(const Sensor& sensor, const SensorBias& prior_std);
  void set_prior_covariance(const SensorBias& prior_std);

  template <int D>
  Covariance<D> fixed_covariance() const {
    return covariance_.template topLeftCorner<D, D>();
  }

  // Σ, and its lower Cholesky factor L for BiasCorrection::g_scaled (Σ is positive definite: a
  // prior of positive entries, or a settled estimate, which factored).
  template <typename Cov>
  void set_covariance(const Cov& covariance);

  Estimate estimate_;
  SensorBias bias_;
  /// Σ of the settled estimate, of its size (at most the three offsets and the clock).
  Square covariance_;
  Square factor_;
  Offsets move_;
  Square narrowing_;
};

}  // namespace skyfuse
