#pragma once
// Tracks and detections of a position-and-velocity sensor for the associators' tests: priors of
// unit covariance, detections of unit noise, each at a given position.

#include <span>
#include <vector>

#include "skyfuse/metrics/chi_square.hpp"
#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/picture/associator.hpp"
#include "skyfuse/picture/hypothesiser.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/picture/tracker_config.hpp"

namespace skyfuse::testing {

using PvSensor = PositionVelocity<6>;

inline GaussianState<6> track_at(const Vector3& position) {
  GaussianState<6> prior;
  prior.mean.setZero();
  prior.mean.head<3>() = position;
  prior.covariance = Covariance<6>::Identity();
  return prior;
}

inline Vector<6> detection_at(const Vector3& position) {
  Vector<6> z = Vector<6>::Zero();
  z.head<3>() = position;
  return z;
}

inline Scan scan_of(const std::vector<Vector<6>>& detections) {
  Scan scan{3, Covariance<6>::Identity(), {}};
  scan.detections.reserve(detections.size());
  for (const Vector<6>& z : detections) scan.detections.emplace_back(z);
  return scan;
}

inline const double kGate = chi_square_quantile(0.9999, 6.0);

/// The hypotheses of `scan` against `tracks`, decided by the associator named `name`.
inline ScanAssociation decide(const char* name, const std::vector<GaussianState<6>>& tracks,
                              const Scan& scan, std::size_t max_detections = 4096,
                              const DetectionPrior& prior = {}) {
  AssociationConfig config;
  config.associator = name;
  config.max_detections_per_scan = max_detections;
  AssociationWork work;
  hypothesise(std::span<const GaussianState<6>>(tracks), PvSensor(), scan, kGate, max_detections,
              true, IdentityMask{}, work.hypothesiser, work.hypotheses);
  ScanAssociation out;
  find_associator(name)->associate(work.hypotheses, prior, config, work, out);
  return out;
}

}  // namespace skyfuse::testing
