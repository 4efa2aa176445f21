#pragma once
/// \file
/// The fusion center's tracker: one stacked-measurement EKF update per step over every
/// station's raw measurement, then a prediction to the next step.

#include <span>
#include <type_traits>

#include "skyfuse/fusion/mixed_stacked_ekf.hpp"
#include "skyfuse/fusion/stacked_ekf.hpp"
#include "skyfuse/registry/sensor_pack.hpp"

namespace skyfuse {

/// The stacked update for stations of one sensor type (fixed blocks), or of a pack (any mix).
template <int N, typename Sensor>
using StackedFor = std::conditional_t<IsSensorPack<Sensor>::value, MixedStackedEkf<N, Sensor>,
                                      StackedEkf<N, Sensor>>;

/// The center's tracker over the motion model `Model`, for stations with sensors `Sensor` (one
/// sensor type, or a SensorPack when they differ).
template <typename Model, typename Sensor>
class CentralTracker {
 public:
  static constexpr int kDim = Model::kDim;
  using State = GaussianState<kDim>;
  using Observation = ObservationFor<Sensor>;

  CentralTracker(const Model& motion, const State& initial) : motion_(motion), estimate_(initial) {}

  /// The stacked update for this step (`Observations`: a random-access range of Observation);
  /// on failure the estimate is unchanged.
  template <typename Observations>
  UpdateReport update(const Observations& observations) {
    return stacked_.update(estimate_, observations);
  }
  /// The stacked update of the observations `stacked` points to, as update() makes it: what a
  /// round stacks (round_rule.hpp). Defined in central_tracker_impl.hpp and compiled once per
  /// configuration group and sensor in core (src/tracking/filter_rounds_shard.cpp), so that the
  /// Monte Carlo and the center process link it.
  UpdateReport update_stacked(std::span<const Observation* const> stacked);
  void predict() { skyfuse::predict(estimate_, motion_); }
  const State& estimate() const { return estimate_; }
  /// Replaces the estimate: a fixed-lag re-fusion going back to a round's prior.
  void reset_to(const State& estimate) { estimate_ = estimate; }

 private:
  Model motion_;
  State estimate_;
  StackedFor<kDim, Sensor> stacked_;
};

}  // namespace skyfuse
