#pragma once
/// \file
/// What every station runs in the decentralised scheme. All peers hold the same prior; each
/// turns its own measurement into an information increment, every peer fuses all increments
/// in ascending station order, and all predict. Same prior + same increments = same bits.

#include <span>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"

namespace skyfuse {

using Increment9 = InformationIncrement<9>;

class PeerTracker {
 public:
  PeerTracker(const ConstantAcceleration3D& motion, const GaussianState<9>& initial)
      : motion_(motion), estimate_(initial) {}

  /// This station's increment against the current (common) prior.
  NumericalStatus make_increment(int station_id, const StationSensor& sensor, const Vector3& z,
                                 const Covariance<3>& noise, Increment9& out) const {
    return compute_increment(station_id, estimate_, sensor, z, noise, out);
  }
  /// Fuses every station's increment (ascending id; weights[i] for increments[i]).
  NumericalStatus fuse(std::span<const Increment9> increments, std::span<const double> weights) {
    return fuse_increments(estimate_, increments, weights, estimate_, &information_);
  }
  /// Y = P^-1 of the estimate after the last fuse().
  const Covariance<9>& information() const { return information_; }
  void predict() { skyfuse::predict(estimate_, motion_); }
  const GaussianState<9>& estimate() const { return estimate_; }

 private:
  ConstantAcceleration3D motion_;
  GaussianState<9> estimate_;
  Covariance<9> information_ = Covariance<9>::Identity();
};

}  // namespace skyfuse
