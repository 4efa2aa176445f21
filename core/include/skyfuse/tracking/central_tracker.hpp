#pragma once
/// \file
/// The fusion center's tracker: one stacked-measurement EKF update per step over every
/// station's raw measurement, then a prediction to the next step.

#include <span>

#include "skyfuse/fusion/stacked_ekf.hpp"
#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"

namespace skyfuse {

using StationObservation9 = StationObservation<StationSensor>;

class CentralTracker {
 public:
  CentralTracker(const ConstantAcceleration3D& motion, const GaussianState<9>& initial)
      : motion_(motion), estimate_(initial) {}

  /// The stacked update for this step; on failure the estimate is unchanged.
  UpdateReport update(std::span<const StationObservation9> observations) {
    return stacked_.update(estimate_, observations);
  }
  void predict() { skyfuse::predict(estimate_, motion_); }
  const GaussianState<9>& estimate() const { return estimate_; }

 private:
  ConstantAcceleration3D motion_;
  GaussianState<9> estimate_;
  StackedEkf<9, StationSensor> stacked_;
};

}  // namespace skyfuse
