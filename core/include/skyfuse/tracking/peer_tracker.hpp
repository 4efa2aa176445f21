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

#include <limits>
#include <span>

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/tracking/peer_contribution.hpp"

namespace skyfuse {

/// What fuse_round() did.
struct RoundFusion {
  NumericalStatus status = NumericalStatus::kOk;
  /// The reference prior differed from this peer's own, which was replaced by it.
  bool resynced = false;
};

/// A peer's tracker over the motion model `Model`; it takes increments from any sensor.
template <typename Model>
class PeerTracker {
 public:
  static constexpr int kDim = Model::kDim;
  using State = GaussianState<kDim>;
  using Increment = InformationIncrement<kDim>;

  PeerTracker(const Model& motion, const State& initial) : motion_(motion), estimate_(initial) {}

  /// This station's increment against the current (common) prior.
  template <typename Sensor>
  NumericalStatus make_increment(int station_id, const Sensor& sensor,
                                 const Vector<Sensor::kMeasDim>& z,
                                 const Covariance<Sensor::kMeasDim>& noise, Increment& out) const {
    return compute_increment(station_id, estimate_, sensor, z, noise, out);
  }
  /// Fuses every station's increment (ascending id; weights[i] for increments[i]).
  template <typename Increments>
  NumericalStatus fuse(const Increments& increments, std::span<const double> weights) {
    const NumericalStatus status =
        fuse_increments(estimate_, increments, weights, estimate_, &information_);
    if (status == NumericalStatus::kOk) information_current_ = true;
    return status;
  }
  /// Fuses one round's increments (ascending station id; weights[i] for increments[i]) onto
  /// `reference`, the prior that came with the lowest-id increment of the round. On failure the
  /// estimate is left as it was, and nothing counts as resynchronised.
  template <typename Increments>
  RoundFusion fuse_round(const State& reference, const Increments& increments,
                         std::span<const double> weights) {
    const bool differs =
        reference.mean != estimate_.mean || reference.covariance != estimate_.covariance;
    RoundFusion result;
    result.status = fuse_increments(reference, increments, weights, estimate_, &information_);
    result.resynced = differs && result.status == NumericalStatus::kOk;
    if (result.status == NumericalStatus::kOk) information_current_ = true;
    return result;
  }
  /// Y = P^-1 of the estimate after the last fuse(): not the current estimate's once it has
  /// been predicted or reset since (see normalized_squared_error()).
  const Covariance<kDim>& information() const { return information_; }
  /// e^T P^-1 e for the current estimate's P (the NEES of an error e). Right after a fusion it
  /// is e^T Y e with the fused information Y = P^-1, which the fusion computed anyway. After a
  /// predict or a reset, with no fusion since (a round that fused nothing: every increment
  /// refused), that Y belongs to an earlier, more certain estimate, so P is factorised instead;
  /// infinity if it is not positive definite.
  double normalized_squared_error(const Vector<kDim>& error) const {
    if (information_current_) return error.dot(information_ * error);
    SmallCholesky<kDim> factor;
    if (!factor.compute(estimate_.covariance)) return std::numeric_limits<double>::infinity();
    return error.dot(factor.solve(error));
  }
  void predict() {
    skyfuse::predict(estimate_, motion_);
    information_current_ = false;
  }
  /// Replaces the estimate: a fixed-lag re-fusion going back to a round's prior.
  void reset_to(const State& estimate) {
    estimate_ = estimate;
    information_current_ = false;
  }
  const State& estimate() const { return estimate_; }

 private:
  Model motion_;
  State estimate_;
  Covariance<kDim> information_ = Covariance<kDim>::Identity();
  bool information_current_ = false;  // information_ is P^-1 of estimate_
};

}  // namespace skyfuse
