#pragma once
// What the center runs on the measurements of a round, by the run's filter kind: the stacked
// EKF (SingleModelCenter), the network IMM's stacked form (ImmCenter), paper 002's stacked
// NCRKF (NcrkfCenter), or the sum of any other part's increments (IncrementCenter). Each takes the
// round's measurements by the round rule, updates, and makes the track; the center process
// (center_process.cpp) moves the samples.

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "skyfuse/core/sorted_ids.hpp"
#include "skyfuse/models/tdoa/tdoa_relative_motion.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/tracking/increment_rules.hpp"
#include "skyfuse/tracking/network_imm.hpp"
#include "skyfuse/tracking/round_rule.hpp"
#include "skyfuse/tracking/tdoa_round.hpp"
#include "skyfuse/transport/imm_wire.hpp"
#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::center {

/// What a single-model center holds and how its track is made, whatever updates it: the tracker
/// and the round that names the stations fused. SingleModelCenter and NcrkfCenter derive from it.
template <typename Tracker, typename Round>
class TrackedCenter {
 public:
  using State = typename Tracker::State;
  static constexpr bool kRefuses = true;  // takes a fixed-lag re-fusion (state, reset_to)

  wire::TrackEstimate track(std::uint64_t run_id, std::uint64_t k, int source_id) const {
    return transport::to_wire(tracker_.estimate(), run_id, static_cast<std::uint32_t>(k), source_id,
                              wire::CENTRAL, round_.contributors());
  }
  void predict() { tracker_.predict(); }
  /// The estimate, and going back to one: a fixed-lag re-fusion of late measurements.
  const State& state() const { return tracker_.estimate(); }
  void reset_to(const State& state) { tracker_.reset_to(state); }

 protected:
  TrackedCenter(Tracker tracker, Round round)
      : tracker_(std::move(tracker)), round_(std::move(round)) {}

  Tracker tracker_;
  Round round_;
};

/// The stacked EKF on `Model`, for stations of `Sensor` (one sensor type, or a SensorPack).
template <typename Model, typename Sensor>
class SingleModelCenter
    : public TrackedCenter<CentralTracker<Model, Sensor>, CentralRound<Model, Sensor>> {
 public:
  using Observation = ObservationFor<Sensor>;

  explicit SingleModelCenter(const RunPlan& plan)
      : SingleModelCenter::TrackedCenter(
            {plan.motion_model<Model>(), plan.initial_estimate<Model>()},
            CentralRound<Model, Sensor>(static_cast<std::size_t>(plan.stations))) {}

  /// observation_at(i): the i-th of `count` participants' observation (ascending id) or null;
  /// on_refused(station_id, why) for each screened out.
  template <typename ObservationAt, typename OnRefused>
  NumericalStatus update(std::size_t count, ObservationAt observation_at, const NisGate& gate,
                         OnRefused on_refused) {
    return this->round_.update(this->tracker_, count, observation_at, gate, on_refused).status;
  }
};

/// The network IMM of `ModeSet` with every mode on the stacked measurement, for stations of one
/// `Sensor`.
template <typename ModeSet, typename Sensor>
class ImmCenter {
 public:
  using Observation = StationObservation<Sensor>;

  explicit ImmCenter(const RunPlan& plan)
      : imm_(NetworkImm<ModeSet>::make(plan.scenario,
                                       plan.initial_estimate<ConstantAcceleration3D>())) {
    contributors_.reserve(static_cast<std::size_t>(plan.stations));
  }

  template <typename ObservationAt, typename OnRefused>
  NumericalStatus update(std::size_t count, ObservationAt observation_at, const NisGate& gate,
                         OnRefused on_refused) {
    return imm_.template update<Observation>(count, observation_at, gate, on_refused,
                                             contributors_);
  }

  wire::TrackEstimate track(std::uint64_t run_id, std::uint64_t k, int source_id) const {
    return transport::imm_track(imm_.filter(), run_id, k, source_id, wire::CENTRAL, contributors_);
  }
  void predict() { imm_.predict(); }
  /// No fixed-lag re-fusion for the IMM yet (its part refuses --refusion-lag).
  static constexpr bool kRefuses = false;

 private:
  typename NetworkImm<ModeSet>::Central imm_;
  std::vector<int> contributors_;
};

/// Paper 002's stacked NCRKF: the center computes each receiver's bias-compensated increment
/// from its raw measurement, as the receiver does, and fuses them onto its own prior by the TDOA
/// round rule, exactly as a peer does (tracking/tdoa_round.hpp), in the peers' order of
/// summation (the tree exchange's, if the run has it): its compensated increments are nearly
/// singular, and another order alone moves the track by 4e-8 m on paper 002.
class NcrkfCenter
    : public TrackedCenter<PeerTracker<TdoaRelativeMotion>, PeerRound<TdoaRelativeMotion>> {
 public:
  using Model = TdoaRelativeMotion;
  static constexpr int kDim = Model::kDim;
  using Sensor = RangeDifferenceSensor<kDim>;
  using Observation = StationObservation<Sensor>;

  explicit NcrkfCenter(const RunPlan& plan)
      : NcrkfCenter(plan, sorted_ascending(plan.participant_ids())) {}

  /// observation_at(i): the i-th of `count` participants' observation (ascending id) or null;
  /// on_refused(station_id, kNotPositive) for each indefinite increment the round was fused
  /// without. The NCRKF has no innovation to gate (its part refuses a gate).
  template <typename ObservationAt, typename OnRefused>
  NumericalStatus update(std::size_t count, ObservationAt observation_at, const NisGate& /*gate*/,
                         OnRefused on_refused) {
    prior_ = tracker_.estimate();
    for (std::size_t i = 0; i < count; ++i) {
      if (const Observation* o = observation_at(i)) increments_[i] = tdoa_contribution(*o);
    }
    return fuse_tdoa_round(
               round_, tracker_, count,
               [&](std::size_t i) {
                 return observation_at(i) != nullptr ? PeerSlot<kDim>{&increments_[i], &prior_}
                                                     : PeerSlot<kDim>{};
               },
               [&](std::size_t i) { on_refused(ids_[i], DropKind::kNotPositive); })
        .status;
  }

 private:
  NcrkfCenter(const RunPlan& plan, std::vector<int> ascending_ids)
      : TrackedCenter({plan.motion_model<Model>(), plan.initial_estimate<Model>()},
                      PeerRound<Model>(ascending_ids, plan.weights_of(ascending_ids),
                                       plan.scenario.exchange.round_fanout())),
        ids_(std::move(ascending_ids)),
        increments_(ids_.size()) {}

  std::vector<int> ids_;                                // participants, ascending
  std::vector<InformationIncrement<kDim>> increments_;  // the round's, by participant
  GaussianState<kDim> prior_;
};

/// How far a reference update of each round's prior lies from the center's: the part's rule
/// names one (the unscented rule: the covariance-form UKF on the stacked measurement).
class ReferenceDistance {
 public:
  template <int N>
  void add(const GaussianState<N>& fused, const GaussianState<N>& reference) {
    const double d = (reference.mean.template head<3>() - fused.mean.template head<3>()).norm();
    ++updates_;
    sum_m_ += d;
    max_m_ = std::max(max_m_, d);
    variance_ratio_sum_ += reference.covariance.template topLeftCorner<3, 3>().trace() /
                           fused.covariance.template topLeftCorner<3, 3>().trace();
  }
  /// Logged when the run ends.
  void report(std::string_view reference) const {
    if (updates_ == 0) return;
    const auto n = static_cast<double>(updates_);
    spdlog::info(
        "{} on the same priors and measurements, over {} updates: position {:.3e} m apart on "
        "average, {:.3e} m at most; its position variance {:.6f} times the center's on average",
        reference, updates_, sum_m_ / n, max_m_, variance_ratio_sum_ / n);
  }

 private:
  std::uint64_t updates_ = 0;
  double sum_m_ = 0.0;
  double max_m_ = 0.0;
  double variance_ratio_sum_ = 0.0;
};

/// The filter of a part with an increment rule (the unscented filter; any new one) on the
/// stacked measurement: the center computes each station's increment from its raw measurement
/// against its own prior, as the station does, and fuses them onto that prior by the round rule.
/// For an increment-form filter the stacked update is the sum of the stations' increments. When
/// the rule names a reference update and the center logs at info level (`-v`), it also measures
/// how far that update lies; otherwise nobody would read the figure, so it is not computed.
template <typename Model, typename Sensor, typename Rule>
class IncrementCenter : public TrackedCenter<PeerTracker<Model>, PeerRound<Model>> {
  static constexpr int kDim = Model::kDim;
  using RoundPrior = typename Rule::template RoundPrior<kDim>;
  static constexpr bool kHasReference = requires(const RoundPrior& p, GaussianState<kDim>& x) {
    p.reference_update(x, std::span<const StationObservation<Sensor>* const>{}, x);
  };

 public:
  using Observation = StationObservation<Sensor>;

  explicit IncrementCenter(const RunPlan& plan)
      : IncrementCenter(plan, sorted_ascending(plan.participant_ids())) {}

  /// observation_at(i): the i-th of `count` participants' observation (ascending id) or null;
  /// on_refused(station_id, why) for each screened out.
  template <typename ObservationAt, typename OnRefused>
  NumericalStatus update(std::size_t count, ObservationAt observation_at, const NisGate& gate,
                         OnRefused on_refused) {
    prior_ = this->tracker_.estimate();
    if (!round_prior_.prepare(prior_)) return NumericalStatus::kNotPositiveDefinite;
    passed_.clear();
    for (std::size_t i = 0; i < count; ++i) {
      const Observation* o = observation_at(i);
      if (o == nullptr) continue;
      const OwnContribution own = round_prior_.contribute(*o, gate, increments_[i]);
      if (own.status != NumericalStatus::kOk) return own.status;
      if (own.refused) {
        on_refused(o->station_id, *own.refused);
      } else {
        passed_.push_back(o);
      }
    }
    const NumericalStatus status = this->round_
                                       .fuse(this->tracker_,
                                             [&](std::size_t i) {
                                               return observation_at(i) != nullptr
                                                          ? PeerSlot<kDim>{&increments_[i], &prior_}
                                                          : PeerSlot<kDim>{};
                                             })
                                       .status;
    if constexpr (kHasReference) {
      if (measure_reference_ && status == NumericalStatus::kOk && !passed_.empty() &&
          round_prior_.reference_update(prior_, std::span<const Observation* const>(passed_),
                                        reference_) == NumericalStatus::kOk) {
        distance_.add(this->tracker_.estimate(), reference_);
      }
    }
    return status;
  }

  /// At the end of the run: how far the rule's reference update lay.
  void report() const {
    if constexpr (kHasReference) distance_.report(RoundPrior::kReferenceName);
  }

 private:
  IncrementCenter(const RunPlan& plan, std::vector<int> ascending_ids)
      : IncrementCenter::TrackedCenter(
            {plan.motion_model<Model>(), plan.initial_estimate<Model>()},
            PeerRound<Model>(ascending_ids, plan.weights_of(ascending_ids))),
        increments_(ascending_ids.size()),
        measure_reference_(spdlog::should_log(spdlog::level::info)) {
    passed_.reserve(ascending_ids.size());
  }

  std::vector<InformationIncrement<kDim>> increments_;  // the round's, by participant
  GaussianState<kDim> prior_;
  RoundPrior round_prior_;                  // the prior prepared once a round for every station
  std::vector<const Observation*> passed_;  // the round's observations that passed screening
  bool measure_reference_;                  // only when report() would be seen
  GaussianState<kDim> reference_;
  ReferenceDistance distance_;
};

/// What the center runs for each registered filter part: a part with an increment rule needs
/// no line (IncrementCenter); the EKF's stacked update, the IMM and the NCRKF have their own.
template <typename Filter, typename Model, typename Sensor>
struct CenterFusionOf {
  using type = IncrementCenter<Model, Sensor, typename Filter::IncrementRule>;
};
template <typename Model, typename Sensor>
struct CenterFusionOf<EkfFilterPart, Model, Sensor> {
  using type = SingleModelCenter<Model, Sensor>;
};
template <typename ModeSet, typename Model, typename Sensor>
struct CenterFusionOf<ImmFilterPart<ModeSet>, Model, Sensor> {
  using type = ImmCenter<ModeSet, Sensor>;
};
template <typename Model, typename Sensor>
struct CenterFusionOf<NcrkfFilterPart, Model, Sensor> {
  using type = NcrkfCenter;
};

}  // namespace skyfuse::center
