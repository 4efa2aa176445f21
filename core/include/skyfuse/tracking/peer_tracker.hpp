#pragma once
/// \file
/// What every station runs in the decentralised scheme. All peers hold the same prior; each
/// turns its own measurement into an information increment, every peer fuses all increments
/// in ascending station order, and all predict. Same prior + same increments = same bits.
///
/// When links lose samples or a station restarts, peers fuse different sets and their priors
/// drift apart. Every increment therefore travels with the prior it was computed against, and
/// each round is fused onto one reference prior: the prior of the lowest-id contribution that
/// arrived. Peers that received the same contributions pick the same reference, so they hold
/// the same bits again after the first complete round, whatever each held before. A restarted
/// station, which has no prior at all, takes its peers' the same way.

#include <span>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"

namespace skyfuse {

using Increment9 = InformationIncrement<9>;

/// A station's increment and the prior it was computed against, as peers receive it.
struct PeerContribution {
  Increment9 increment;
  GaussianState<9> prior;
};

/// What fuse_round() did.
struct RoundFusion {
  NumericalStatus status = NumericalStatus::kOk;
  /// The reference prior differed from this peer's own, which was replaced by it.
  bool resynced = false;
};

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
  /// Fuses one round's increments (ascending station id; weights[i] for increments[i]) onto
  /// `reference`, the prior that came with the lowest-id increment of the round. On failure the
  /// estimate is left as it was, and nothing counts as resynchronised.
  RoundFusion fuse_round(const GaussianState<9>& reference, std::span<const Increment9> increments,
                         std::span<const double> weights) {
    const bool differs =
        reference.mean != estimate_.mean || reference.covariance != estimate_.covariance;
    RoundFusion result;
    result.status = fuse_increments(reference, increments, weights, estimate_, &information_);
    result.resynced = differs && result.status == NumericalStatus::kOk;
    return result;
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
