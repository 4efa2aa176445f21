#pragma once
/// \file
/// The fusion center's tracker: one stacked-measurement EKF update per step over every
/// station's raw measurement, then a prediction to the next step.

#include <span>

#include "skyfuse/fusion/stacked_ekf.hpp"

namespace skyfuse {

/// The center's tracker over the motion model `Model`, for stations with sensors `Sensor`.
template <typename Model, typename Sensor>
class CentralTracker {
 public:
  static constexpr int kDim = Model::kDim;
  using State = GaussianState<kDim>;
  using Observation = StationObservation<Sensor>;

  CentralTracker(const Model& motion, const State& initial) : motion_(motion), estimate_(initial) {}

  /// The stacked update for this step (`Observations`: a random-access range of Observation);
  /// on failure the estimate is unchanged.
  template <typename Observations>
  UpdateReport update(const Observations& observations) {
    return stacked_.update(estimate_, observations);
  }
  void predict() { skyfuse::predict(estimate_, motion_); }
  const State& estimate() const { return estimate_; }

 private:
  Model motion_;
  State estimate_;
  StackedEkf<kDim, Sensor> stacked_;
};

}  // namespace skyfuse
