#pragma once
/// \file
/// A track's error correlated with the biases its registered stations have not learnt yet: the
/// Schmidt, or "consider", update (docs/registration.md, "NEES").
///
/// A registered station's detection, corrected by its settled biases b̂, still carries the
/// error of that estimate, δb = b − b̂ ~ N(0, Σ): z − G b̂ = h(x) + G δb + ν. That error is one
/// and the same in every detection the station makes, so it is no white noise: a track that took
/// it as such (R + G Σ Gᵀ in each detection) believes it averaged it away over a hundred
/// detections, and it has not. Here the track keeps, for each registered station whose
/// detections it took, the cross-covariance of its error with that station's bias error, in the
/// bias's standardised coordinates u (δb = L u, Σ = L Lᵀ, so u ~ N(0, I)): C̃ = Cov(x − x̂, u).
///
/// An update is the joint one of [x; u₁ … u_k] in information form — each station's detection
/// adds [H G̃]ᵀ R⁻¹ [H G̃] (G̃ = G L), which still add up across stations, so that every peer and
/// the center sum the same increments — of which the track keeps its own mean and covariance and
/// the new C̃, but not what it learnt of u: the registration, not the track, estimates the biases
/// (the Schmidt–Kalman filter's rule; its x-part is the joint update's exactly).
///
/// When the registration settles, it has learnt of u: u now lies at m with spread A Aᵀ (m its
/// move, A = L_old⁻¹ L_new). The track takes that as a measurement of u independent of its own
/// error (the registration learnt from every track's detections, not this one's alone):
/// conditioned on it, x̂ += C̃ m, P −= C̃ (I − A Aᵀ) C̃ᵀ, and its C̃ against the new standardised
/// errors is C̃ A (settle_considered). The prior of u is N(0, I) again at the next update.

#include <Eigen/Core>
#include <span>
#include <vector>

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/core/status.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/fusion/information_increment.hpp"

namespace skyfuse {

/// At most a state of kMaxConsideredState entries and kMaxConsideredBias biases per station.
inline constexpr int kMaxConsideredState = 16;
inline constexpr int kMaxConsideredBias = 4;

using ConsideredCross = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                      kMaxConsideredState, kMaxConsideredBias>;
using ConsideredBiasBlock = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                          kMaxConsideredBias, kMaxConsideredBias>;
using ConsideredBiasVector =
    Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxConsideredBias, 1>;

/// A track's error against one registered station's standardised bias error: C̃ (N × D).
struct ConsideredBias {
  int station_id = 0;
  ConsideredCross cross;
  bool operator==(const ConsideredBias&) const = default;
};

/// A track's, ascending station id.
using ConsideredBiases = std::vector<ConsideredBias>;

/// What a registered station's detections of a track add to the joint of the track and that
/// station's u beyond their information increment: Hᵀ R⁻¹ G̃ (N × D), G̃ᵀ R⁻¹ G̃ and
/// G̃ᵀ R⁻¹ (ν + H x̂) — a weighed sum of them for several detections (JPDA's).
struct ConsideredTerms {
  int station_id = 0;
  ConsideredCross cross;
  ConsideredBiasBlock bias;
  ConsideredBiasVector vector;

  /// Zero terms of `state_dim` × `bias_dim`, to sum detections' into.
  void set_zero(int station, int state_dim, int bias_dim) {
    station_id = station;
    cross.setZero(state_dim, bias_dim);
    bias.setZero(bias_dim, bias_dim);
    vector.setZero(bias_dim);
  }
  void add_weighted(const ConsideredTerms& one, double weight) {
    cross += weight * one.cross;
    bias += weight * one.bias;
    vector += weight * one.vector;
  }
};

/// Whether a filter part's tracks (picture/track_filters.hpp) keep their cross-covariances
/// with registered stations' bias errors.
template <typename Tracks>
concept ConsidersBiases = requires {
  requires Tracks::kConsidersBiases;
};

/// A center's observation of a registered station, by its index among a track's observations:
/// its standardised bias Jacobian G L (BiasCorrection::g_scaled).
struct ConsideredObservation {
  std::size_t observation = 0;
  Eigen::MatrixXd g_scaled;
};

/// Detection `z` (already corrected by the settled biases, noise `noise`: the station's own,
/// without G Σ Gᵀ) of the track of prior `prior`, from a station whose standardised bias
/// Jacobian at the prior mean is `g_scaled` (G L): its terms, linearised as its increment is
/// (information_increment.hpp: the same H, innovation and factor of R). False where R does not
/// factor. Defined in considered_terms_impl.hpp, compiled once per state size of a picture whose
/// tracks keep their cross-covariances (picture/state_size_code.hpp).
template <int N, typename Sensor>
bool considered_terms(int station_id, const GaussianState<N>& prior, const Sensor& sensor,
                      const Vector<Sensor::kMeasDim>& z, const Covariance<Sensor::kMeasDim>& noise,
                      const Eigen::Ref<const Eigen::MatrixXd>& g_scaled, ConsideredTerms& out);

/// The joint update (the file's comment) of a track of mean `mean` and covariance `covariance`
/// (N entries) holding `considered`: `delta_information` and `delta_vector`, the sum of every
/// station's weighed increment, and `terms`, the registered stations' (ascending station id,
/// weights[i] belongs to terms[i]). Writes the posterior mean and covariance over the prior's,
/// and `considered` becomes the posterior's C̃ for every station it held or `terms` names, in
/// ascending station id. On failure nothing is written.
NumericalStatus fuse_considered(Eigen::Ref<Eigen::VectorXd> mean,
                                Eigen::Ref<Eigen::MatrixXd> covariance,
                                ConsideredBiases& considered,
                                const Eigen::Ref<const Eigen::MatrixXd>& delta_information,
                                const Eigen::Ref<const Eigen::VectorXd>& delta_vector,
                                std::span<const ConsideredTerms> terms,
                                std::span<const double> weights);

/// The same for a Gaussian of fixed size, with its increments as fuse_increments takes them
/// (increments[i] weighed by increment_weights[i]).
template <int N, typename Increments>
NumericalStatus fuse_considered(GaussianState<N>& state, ConsideredBiases& considered,
                                const Increments& increments,
                                std::span<const double> increment_weights,
                                std::span<const ConsideredTerms> terms,
                                std::span<const double> term_weights) {
  Covariance<N> information = Covariance<N>::Zero();
  Vector<N> vector = Vector<N>::Zero();
  for (std::size_t i = 0; i < increments.size(); ++i) {
    information.noalias() += increment_weights[i] * increments[i].delta_information;
    vector.noalias() += increment_weights[i] * increments[i].delta_vector;
  }
  // In place: the update writes nothing where it fails.
  return fuse_considered(state.mean, state.covariance, considered, information, vector, terms,
                         term_weights);
}

/// A track of mean `mean` and covariance `covariance` (N entries) holding `c` against a station
/// whose registration settled: moved by `move` (m) and narrowed by `narrowing` (A), as the
/// file's comment says. Nothing happens where their sizes are not C̃'s (the station settled
/// nothing).
void settle_considered(Eigen::Ref<Eigen::VectorXd> mean, Eigen::Ref<Eigen::MatrixXd> covariance,
                       ConsideredBias& c, const Eigen::Ref<const Eigen::VectorXd>& move,
                       const Eigen::Ref<const Eigen::MatrixXd>& narrowing);

/// The same for a Gaussian of fixed size.
template <int N>
void settle_considered(GaussianState<N>& state, ConsideredBias& c,
                       const Eigen::Ref<const Eigen::VectorXd>& move,
                       const Eigen::Ref<const Eigen::MatrixXd>& narrowing) {
  settle_considered(state.mean, state.covariance, c, move, narrowing);
}

/// A track's C̃ carried through its time update: F C̃, F the motion's Jacobian at the prior mean
/// (u does not move).
inline void predict_considered(const Eigen::Ref<const Eigen::MatrixXd>& transition,
                               ConsideredBiases& considered) {
  for (ConsideredBias& c : considered) c.cross = transition.lazyProduct(c.cross).eval();
}

}  // namespace skyfuse
