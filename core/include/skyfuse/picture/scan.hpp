#pragma once
/// \file
/// A station's scan: the unlabelled list of what its sensor reported in one step — aircraft
/// detected, false alarms — in an order that says nothing of which is which: what the tracker
/// is given. The simulator that makes one from the truth is traffic/scan_simulation.hpp.
///
/// A picture's stations may carry different sensors (picture/picture_sensor.hpp), so a
/// detection holds as many values as its station's sensor reports, up to kMaxDetectionDim,
/// without a heap. The arithmetic on it is its sensor's own, on fixed sizes (fixed_detection,
/// fixed_noise): the same bits as a scan typed by its sensor.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/picture/address.hpp"
#include "skyfuse/picture/identification.hpp"

namespace skyfuse {

/// The most values one detection of a picture's sensor holds (a position and a velocity).
inline constexpr int kMaxDetectionDim = 6;

/// One detection: its sensor's measurement, of that sensor's size.
using Detection = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxDetectionDim, 1>;
/// The noise R of a station's detections, of its sensor's size.
using DetectionNoise = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                     kMaxDetectionDim, kMaxDetectionDim>;

/// A detection as its sensor's fixed-size measurement (its size must be M).
template <int M>
Vector<M> fixed_detection(const Detection& z) {
  return z.template head<M>();
}
/// A station's noise as its sensor's fixed-size R (its size must be M x M).
template <int M>
Covariance<M> fixed_noise(const DetectionNoise& noise) {
  return noise.template topLeftCorner<M, M>();
}

/// One station's scan; its sensor (and site) is the station's.
struct Scan {
  int station_id = 0;
  DetectionNoise noise;  ///< R of every detection of the station
  std::vector<Detection> detections;
  /// Each detection's address (picture/address.hpp), in detection order; empty when none
  /// has one (a primary radar's scan).
  std::vector<Address> addresses{};
  /// Each detection's identification (picture/identification.hpp), in detection order; empty
  /// when none has one. The tracker does not read it.
  std::vector<Identification> identifications{};
  /// Each detection's own σ of each of its values where its report states one (an ADS-B
  /// report's NACp and NACv, I021/090), 0 for a value it says nothing of, in detection order;
  /// empty when no detection's report states any. Its R is then reported_noise's.
  std::vector<Detection> reported_std{};
};

/// Detection j's reported σ (Scan::reported_std), or an empty one where the scan has none.
inline const Detection& reported_std_at(std::span<const Detection> reported, std::size_t j) {
  static const Detection kNone;
  return reported.empty() ? kNone : reported[j];
}

/// The R of a detection of a station of noise `noise` whose report states its own σ of some
/// values (`reported`, 0 for a value it says nothing of; empty: none): each such value's row
/// and column rescaled so that its variance is the reported σ², its correlations with the
/// others kept, so that R stays positive definite. `noise` itself where nothing is reported.
template <int M>
Covariance<M> reported_noise(const Covariance<M>& noise, const Detection& reported) {
  if (reported.size() == 0) return noise;
  Covariance<M> r = noise;
  for (int i = 0; i < M; ++i) {
    if (reported(i) <= 0.0) continue;
    const double scale = reported(i) / std::sqrt(noise(i, i));
    r.row(i) *= scale;
    r.col(i) *= scale;
  }
  return r;
}

/// Whether two detections hold the same values, bit for bit (any sizes).
inline bool same_detection(const Detection& a, const Detection& b) {
  return a.size() == b.size() && a == b;
}

}  // namespace skyfuse
