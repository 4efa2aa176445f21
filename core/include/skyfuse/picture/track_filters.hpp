#pragma once
/// \file
/// What a track's filter is, for each kind of filter part, as the picture's peers and center
/// use it. The track table (track_table.hpp), the stations' reports (peer_picture.hpp) and the
/// center's updates (central_picture.hpp) are written once over these:
///
///  - peers: `State` (one track's filter), `Contribution` (what a station sends for one track),
///    `predict`, `estimate` (the Gaussian the gate, management and metrics read, in kDim
///    entries whose first three are the position), `start` (a new track's filter from a
///    Gaussian in kDim), `contribute` (a station's contribution for one detection against the
///    track's prior) and `fuse` (every station's contributions, ascending station id);
///  - center: the same `State` family with `update` (the detections assigned to a track, in one
///    update).
///
/// A filter part with an increment rule on one motion model needs no line here
/// (PeerModelTracks, CenterModelTracks); the IMM has its own (PeerImmTracks, CenterImmTracks).

#include <span>
#include <stdexcept>
#include <type_traits>
#include <variant>
#include <vector>

#include "skyfuse/core/indirect_view.hpp"
#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/mixed_stacked_ekf.hpp"
#include "skyfuse/fusion/relinearised_increment.hpp"
#include "skyfuse/fusion/stacked_ekf.hpp"
#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/picture/imm_picture_steps.hpp"
#include "skyfuse/picture/picture_sensor.hpp"
#include "skyfuse/registration/considered_biases.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/scenario/truth.hpp"
#include "skyfuse/tracking/increment_rules_impl.hpp"
#include "skyfuse/tracking/network_imm.hpp"
#include "skyfuse/tracking/round_rule.hpp"
#include "skyfuse/validation/nis_gate.hpp"

namespace skyfuse {

/// A track of one motion model: its Gaussian, predicted by the model.
template <typename Model>
class ModelTracks {
 public:
  static constexpr int kDim = Model::kDim;
  static constexpr int kNeesDof = kDim;
  using State = GaussianState<kDim>;

  /// `initial_variance`: a new track's variances outside its position and velocity.
  ModelTracks(const Model& motion, const Vector<kDim>& initial_variance)
      : motion_(motion), initial_variance_(initial_variance) {}

  void predict(State& state) const { skyfuse::predict(state, motion_); }
  /// A track's cross-covariances with its stations' bias errors through the time update of
  /// `prior` (call before predict(prior)).
  void predict_considered(const State& prior, ConsideredBiases& considered) const {
    if (!considered.empty()) skyfuse::predict_considered(motion_.jacobian(prior.mean), considered);
  }
  static const GaussianState<kDim>& estimate(const State& state) { return state; }
  static State start(const GaussianState<kDim>& initial) { return initial; }
  static Vector<kDim> from_kinematics(const Vector<kKinematicsDim>& x) {
    return Model::from_kinematics(x);
  }
  const Vector<kDim>& initial_variance() const { return initial_variance_; }

 private:
  Model motion_;
  Vector<kDim> initial_variance_;
};

/// The peers' side for a part with an increment rule `Rule`: one increment per detection,
/// summed in ascending station id.
template <typename Model, typename Rule>
class PeerModelTracks : public ModelTracks<Model> {
 public:
  static constexpr int kDim = Model::kDim;
  using State = GaussianState<kDim>;
  using Contribution = InformationIncrement<kDim>;
  /// The EKF's tracks keep their cross-covariances with registered stations' bias errors
  /// (registration/considered_biases.hpp): its increment is the joint update's x-part as it
  /// is linearised. Other parts take those errors as white noise in R.
  static constexpr bool kConsidersBiases = std::is_same_v<Rule, EkfIncrementRule>;
  /// Whether the part's increment is H, h and R at a point, so that it can be relinearised
  /// (fusion/relinearised_increment.hpp): the EKF's.
  static constexpr bool kRelinearises = std::is_same_v<Rule, EkfIncrementRule>;

  /// `relinearisations`: the iterated steps to each detection's linearisation point
  /// (tracker.updater; 0 for a part that does not relinearise).
  PeerModelTracks(const Model& motion, const Vector<kDim>& initial_variance,
                  int relinearisations = 0)
      : ModelTracks<Model>(motion, initial_variance), relinearisations_(relinearisations) {}

  /// Observation `o`'s contribution against the track's prior `state`, linearised at the
  /// point the tracker's relinearisations give (linearised()).
  template <typename Sensor>
  NumericalStatus contribute(const State& state, const StationObservation<Sensor>& o,
                             Contribution& out) const {
    if constexpr (kRelinearises) {
      // Only then a copy of the prior: the default path takes it as it is.
      if (relinearisations_ > 0) return contribute_at(linearised(state, o), o, out);
    }
    return contribute_at(state, o, out);
  }
  /// `state` with its mean at observation `o`'s linearisation point: the state itself unless
  /// the tracker relinearises.
  template <typename Sensor>
  State linearised(const State& state, const StationObservation<Sensor>& o) const {
    if constexpr (kRelinearises) return relinearised_prior(state, o, relinearisations_);
    return state;
  }
  /// The contribution linearised at `point`'s mean (the prior's, or linearised()'s).
  template <typename Sensor>
  static NumericalStatus contribute_at(const State& point, const StationObservation<Sensor>& o,
                                       Contribution& out) {
    const NisGate no_gate;  // the assignment's gate screened the pair
    const OwnContribution own = Rule::contribute(point, o, no_gate, out);
    return own.refused ? NumericalStatus::kNotPositiveDefinite : own.status;
  }
  static NumericalStatus fuse(State& state, std::span<const Contribution* const> contributions,
                              std::span<const double> weights) {
    return fuse_increments(state, IndirectView<Contribution>(contributions), weights, state);
  }
  /// fuse() for a track that keeps its cross-covariances `considered`, with the registered
  /// stations' `terms` (ascending station id, terms[i] weighed by term_weights[i]).
  static NumericalStatus fuse_considered(State& state, ConsideredBiases& considered,
                                         std::span<const Contribution* const> contributions,
                                         std::span<const double> weights,
                                         std::span<const ConsideredTerms> terms,
                                         std::span<const double> term_weights) {
    return skyfuse::fuse_considered(state, considered, IndirectView<Contribution>(contributions),
                                    weights, terms, term_weights);
  }
  /// A station's contribution of several detections (JPDA's): a zero sum, then each
  /// detection's increment weighed by its pair's weight.
  static void start_sum(Contribution& sum, int station_id) { sum.set_zero(station_id); }
  static void add_weighted(Contribution& sum, const Contribution& one, double weight) {
    sum.delta_information.noalias() += weight * one.delta_information;
    sum.delta_vector.noalias() += weight * one.delta_vector;
  }

 private:
  int relinearisations_ = 0;
};

/// The center's update of a track from its increments: one per station (ascending, as the
/// observations come; a station with several detections of the track, JPDA's, each with its
/// noise already weighed, adds theirs up), fused onto the prior with the stations' weights.
/// Holds its buffers from track to track.
template <int N>
class CenterIncrementFusion {
 public:
  /// `contribute(o, out)` writes observation o's increment against `state`.
  template <typename Contribute>
  bool update(GaussianState<N>& state, std::span<const PictureObservation<N>> observations,
              std::span<const double> weights, Contribute&& contribute) {
    increments_.clear();
    station_weights_.clear();
    InformationIncrement<N> one;
    for (std::size_t i = 0; i < observations.size(); ++i) {
      int station_id = 0;
      const NumericalStatus contributed = std::visit(
          [&](const auto& o) {
            station_id = o.station_id;
            return contribute(o, one);
          },
          observations[i]);
      if (contributed != NumericalStatus::kOk) return false;
      if (!increments_.empty() && increments_.back().station_id == station_id) {
        increments_.back().delta_information += one.delta_information;
        increments_.back().delta_vector += one.delta_vector;
      } else {
        increments_.push_back(one);
        station_weights_.push_back(weights[i]);
      }
    }
    return fuse_increments(state, std::span<const InformationIncrement<N>>(increments_),
                           station_weights_, state) == NumericalStatus::kOk;
  }

 private:
  std::vector<InformationIncrement<N>> increments_;
  std::vector<double> station_weights_;
};

/// The center's side for the EKF: one stacked update of a track's detections, the peers' sum
/// for weights of 1, as the single-target center's.
template <typename Model>
class CenterStackedTracks : public ModelTracks<Model> {
 public:
  static constexpr int kDim = Model::kDim;
  using State = GaussianState<kDim>;
  /// `relinearisations`: as the peers' (PeerModelTracks).
  CenterStackedTracks(const Model& motion, const Vector<kDim>& initial_variance,
                      int relinearisations = 0)
      : ModelTracks<Model>(motion, initial_variance), relinearisations_(relinearisations) {}

  /// Stations of one sensor kind take the stacked update of that sensor's fixed-size blocks;
  /// of several, the one assembled at run time. A tracker that relinearises takes each
  /// detection's increment at its own point instead, as the peers do (fusion/
  /// relinearised_increment.hpp): a stacked update has one point for all. Compiled once per motion
  /// model in core (src/picture/center_stacked_tracks.cpp), not in every file of the picture that
  /// runs the EKF: inline, each sensor's stacked update made the center's and the sweep's shards
  /// the build's largest files (docs/testing.md).
  bool update(State& state, std::span<const PictureObservation<kDim>> observations,
              std::span<const double> weights);

  /// As the peers' (PeerModelTracks::kConsidersBiases).
  static constexpr bool kConsidersBiases = true;
  /// update() for a track that keeps its cross-covariances `considered`: the peers' joint
  /// update (registration/considered_biases.hpp) of every observation's increment (station
  /// weights[i]), with `registered`'s terms for the observations of registered stations.
  bool update_considered(State& state, ConsideredBiases& considered,
                         std::span<const PictureObservation<kDim>> observations,
                         std::span<const ConsideredObservation> registered,
                         std::span<const double> weights);

 private:
  template <typename Sensor>
  using StackedOf = StackedEkf<kDim, Sensor>;
  int relinearisations_ = 0;
  CenterIncrementFusion<kDim> relinearised_;
  PictureObservationBuffers<kDim> buffers_;
  // update_considered's, kept from track to track.
  struct ConsideredWork {
    std::vector<InformationIncrement<kDim>> increments;
    std::vector<ConsideredTerms> terms;
    std::vector<double> term_weights;
  };
  ConsideredWork considered_work_;
  ForEachPictureSensor<kDim, StackedOf> stacked_;
  MixedStackedEkf<kDim, PictureSensorPack<kDim>> mixed_;
};

/// The center's side for another part with an increment rule (the unscented filter): its own
/// increments of the raw detections against its own prior, fused onto it, as the single-target
/// center does (sim/increment_run_stepper.hpp).
template <typename Model, typename Rule>
class CenterIncrementTracks : public ModelTracks<Model> {
 public:
  static constexpr int kDim = Model::kDim;
  using State = GaussianState<kDim>;
  /// `relinearisations` is refused for a part that does not relinearise (the scenario's
  /// loader refuses it first).
  CenterIncrementTracks(const Model& motion, const Vector<kDim>& initial_variance,
                        int relinearisations = 0)
      : ModelTracks<Model>(motion, initial_variance) {
    if (relinearisations != 0) {
      throw std::invalid_argument("tracker.updater.relinearisations: the EKF's alone");
    }
  }

  bool update(State& state, std::span<const PictureObservation<kDim>> observations,
              std::span<const double> weights) {
    return fusion_.update(state, observations, weights, [&](const auto& o, auto& out) {
      return PeerModelTracks<Model, Rule>::contribute_at(state, o, out);
    });
  }

 private:
  CenterIncrementFusion<kDim> fusion_;
};

/// A track of the network IMM of mode set `Set` (tracking/network_imm.hpp), in its common
/// state [p; v; a; omega]: the scenario's modes, switching and turn-rate variance.
template <typename Set, typename Filter>
class ImmTracks {
 public:
  static constexpr int kDim = KinematicState::kDim;
  /// As the single-target IMM's: the position and velocity every mode keeps.
  static constexpr int kNeesDof = 6;
  using State = Filter;

  /// `scenario` must outlive the tracks.
  explicit ImmTracks(const Scenario& scenario) : scenario_(&scenario) {
    initial_variance_.template head<ConstantAcceleration3D::kDim>() =
        scenario.filter.initial_covariance_diag;
    initial_variance_(KinematicState::kTurnRate) = scenario.filter.imm.initial_turn_rate_variance;
  }

  static void predict(State& state) { state.predict(); }
  static GaussianState<kDim> estimate(const State& state) { return state.filter().estimate(); }
  /// Every mode equally likely, each from `initial`'s [p; v; a] and the turn-rate variance.
  State start(const GaussianState<kDim>& initial) const {
    GaussianState<ConstantAcceleration3D::kDim> ca;
    ca.mean = initial.mean.template head<ConstantAcceleration3D::kDim>();
    ca.covariance =
        initial.covariance
            .template topLeftCorner<ConstantAcceleration3D::kDim, ConstantAcceleration3D::kDim>();
    return State(NetworkImm<Set>::make(*scenario_, ca));
  }
  static Vector<kDim> from_kinematics(const Vector<kKinematicsDim>& x) {
    Vector<kDim> common = Vector<kDim>::Zero();
    common.template head<kKinematicsDim>() = x;
    return common;
  }
  const Vector<kDim>& initial_variance() const { return initial_variance_; }

 private:
  const Scenario* scenario_;  // a pointer, so that tracks can be copied and assigned
  Vector<kDim> initial_variance_ = Vector<kDim>::Zero();
};

/// Whether a track's filter state is an IMM's (a state per mode and the mode probabilities,
/// PeerImmTracks' and CenterImmTracks') rather than one Gaussian.
template <typename State>
concept ImmTrackState = requires(const State& s) {
  s.filter().mode_probabilities();
};

/// The peers' side of the IMM: per mode, each station's increment and likelihood terms
/// against the mode's prior; the modes and probabilities fused as the single-target peers do.
template <typename Set>
class PeerImmTracks : public ImmTracks<Set, typename NetworkImm<Set>::Peer> {
 public:
  using Peer = typename NetworkImm<Set>::Peer;
  using ImmTracks<Set, Peer>::ImmTracks;
  using State = Peer;
  using Contribution = typename Peer::Contribution;

  template <typename Sensor>
  static NumericalStatus contribute(const State& state, const StationObservation<Sensor>& o,
                                    Contribution& out) {
    const OwnContribution own = ImmPictureSteps<Set, Sensor>::contribute(state, o, out);
    return own.refused ? NumericalStatus::kNotPositiveDefinite : own.status;
  }
  static NumericalStatus fuse(State& state, std::span<const Contribution* const> contributions,
                              std::span<const double> weights) {
    return state.fuse_round(contributions, weights).status;
  }
};

/// The center's side of the IMM: every mode takes the stacked update of a track's detections,
/// weighed by the stacked likelihood.
template <typename Set>
class CenterImmTracks : public ImmTracks<Set, typename NetworkImm<Set>::Central> {
 public:
  using Central = typename NetworkImm<Set>::Central;
  using ImmTracks<Set, Central>::ImmTracks;
  using State = Central;
  static constexpr int kDim = KinematicState::kDim;

  bool update(State& state, std::span<const PictureObservation<kDim>> observations,
              std::span<const double> /*weights*/) {
    return by_sensor_kind<kDim>(
        observations, buffers_,
        [&]<typename Sensor>(std::span<const StationObservation<Sensor>> one_kind) {
          return ImmPictureSteps<Set, Sensor>::update(state, one_kind) == NumericalStatus::kOk;
        },
        []() -> bool {
          // The IMM's stacked update is of one sensor kind's blocks (tracking/imm_network.hpp).
          throw std::logic_error("the IMM's center takes stations of one sensor kind");
        });
  }

 private:
  PictureObservationBuffers<kDim> buffers_;
};

}  // namespace skyfuse
