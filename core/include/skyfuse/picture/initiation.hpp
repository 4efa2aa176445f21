#pragma once
/// \file
/// Starting tracks from detections no track took. A new aircraft leaves such detections at
/// several stations; whether they belong together is the one decision that couples stations,
/// so every peer takes it itself, by the same rule, from the same published inputs: every
/// station's unassociated detections, in (station id, detection index) order.
///
/// The rule, greedy and deterministic: each detection in that order, not yet used, opens a
/// group; each later detection of a station not yet in the group joins it if its position
/// agrees with the group's fused position (a chi-square test of the difference against the sum
/// of their covariances); a group of at least `min_stations` detections becomes a tentative
/// track at its fused position, named after the detection that opened it.
///
/// Identity (identity.hpp): a group holds at most one address, and a detection of another
/// address does not join it; a group with an address is a cooperative report of the aircraft
/// itself and starts a track from one station, with the velocity of its first detection that
/// reports one; an address starts one track a round.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/models/height_band.hpp"
#include "skyfuse/picture/track.hpp"
#include "skyfuse/picture/tracker_config.hpp"

namespace skyfuse {

/// Where one unassociated detection puts the target, with the covariance of that position.
struct PositionFix {
  int station_id = 0;
  std::uint32_t detection = 0;  ///< its index in the station's scan
  Vector3 position = Vector3::Zero();
  Covariance<3> covariance = Covariance<3>::Identity();
  Covariance<3> information = Covariance<3>::Identity();  ///< covariance^-1 = H^T R^-1 H
  Address address = kNoAddress;                           ///< the detection's (picture/address.hpp)
  /// The velocity the detection reports, with its covariance, for a sensor that reports one.
  std::optional<Vector3> velocity{};
  Covariance<3> velocity_covariance = Covariance<3>::Identity();
};

/// A sensor whose detection reports the target's velocity as well as its position.
template <typename Sensor>
concept ReportsVelocity = requires(const typename Sensor::Measurement& z) {
  { Sensor::velocity_of(z) } -> std::convertible_to<Vector3>;
  { Sensor::kVelocityEntries } -> std::convertible_to<int>;
};

/// The fix of detection `z` (noise R) of a sensor one of whose detections fixes a position:
/// the position the sensor inverts it to, and (H^T R^-1 H)^-1 with H the sensor's Jacobian in
/// the position there; for a sensor that assumes a band of heights, the band's variance is a
/// prior on the height, added to H^T R^-1 H. None where that loses rank (a radar's zenith).
template <typename Sensor>
std::optional<PositionFix> fix_position(int station_id, std::uint32_t detection,
                                        const Sensor& sensor, const Vector<Sensor::kMeasDim>& z,
                                        const Covariance<Sensor::kMeasDim>& noise) {
  constexpr int M = Sensor::kMeasDim;
  PositionFix fix{station_id, detection, sensor.position_of(z), Covariance<3>::Identity(),
                  Covariance<3>::Identity()};
  Vector<Sensor::kStateDim> x = Vector<Sensor::kStateDim>::Zero();
  x.template head<3>() = fix.position;
  const Matrix<M, 3> h = sensor.jacobian(x).template leftCols<3>();
  SmallCholesky<M> r_factor;
  if (!r_factor.compute(noise)) return std::nullopt;
  Matrix<M, 3> r_inv_h;
  for (int c = 0; c < 3; ++c) r_inv_h.col(c) = r_factor.solve(h.col(c));
  Covariance<3> information = h.transpose() * r_inv_h;
  symmetrize(information);
  if constexpr (TakesHeightBand<Sensor>) {
    information(2, 2) += 1.0 / sensor.height_band().variance_m2();
  }
  SmallCholesky<3> info_factor;
  if (!info_factor.compute(information)) return std::nullopt;
  fix.covariance = info_factor.inverse();
  fix.information = information;
  if constexpr (ReportsVelocity<Sensor>) {
    fix.velocity = Sensor::velocity_of(z);
    fix.velocity_covariance =
        noise.template block<3, 3>(Sensor::kVelocityEntries, Sensor::kVelocityEntries);
  }
  return fix;
}

/// A track to start: where, how certain, from which detections.
struct NewTrack {
  TrackId id = 0;
  Vector3 position = Vector3::Zero();
  Covariance<3> covariance = Covariance<3>::Identity();
  std::vector<int> stations;       ///< whose detections started it, ascending
  std::vector<std::size_t> fixes;  ///< their fixes, as indices into initiate_tracks's, ascending
  Address address = kNoAddress;
  /// For a track started by an addressed detection of a sensor that reports a velocity: that
  /// velocity and its covariance; none otherwise (the initiation's velocity spread).
  std::optional<Vector3> velocity{};
  Covariance<3> velocity_covariance = Covariance<3>::Identity();
};

/// The chi-square(3) quantile two fixes' difference is tested against to join
/// (config.gate_probability): an iterative solve, so a tracker computes it once.
double join_gate(const InitiationConfig& config);

/// The tracks `fixes` (in (station id, detection index) order) start at `step`, joining fixes
/// within `gate` (join_gate(config)).
std::vector<NewTrack> initiate_tracks(std::span<const PositionFix> fixes, std::uint64_t step,
                                      const InitiationConfig& config, double gate);
/// The same, computing the gate.
inline std::vector<NewTrack> initiate_tracks(std::span<const PositionFix> fixes, std::uint64_t step,
                                             const InitiationConfig& config) {
  return initiate_tracks(fixes, step, config, join_gate(config));
}

}  // namespace skyfuse
