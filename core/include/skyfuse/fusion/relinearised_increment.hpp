#pragma once
/// \file
/// A station's increment linearised where its own detection puts the track, not at the prior.
///
/// The EKF's increment (information_increment.hpp) takes H and h at the prior mean x⁻. A track
/// a few rounds old, or one whose velocity is still a guess, can be hundreds of metres off;
/// near a radar that is a large angle, and the linearisation error becomes a bias the
/// covariance does not know: a track started 6 km from a radar came out 50 m off with an 8 m σ
/// (docs/picture.md, "Relinearised increments"). With little process noise the filter never
/// forgets it.
///
/// The iterated EKF's step, one station at a time: from the same prior, the station's own
/// posterior mean linearised at the last point x_i,
///
///   x_{i+1} = x⁻ + P Hᵢᵀ (Hᵢ P Hᵢᵀ + R)⁻¹ (z − h(x_i) − Hᵢ (x⁻ − x_i)),   x_0 = x⁻,
///
/// and the increment linearised at the last point, dQ = HᵀR⁻¹H, dy = HᵀR⁻¹(z − h(x_k) + H x_k)
/// (its own linearisation of the detection; the sum of such increments onto the common prior
/// is still the information form's). Every input is the common prior and the station's own
/// detection, so every peer and the center compute the same point. For a sensor linear in the
/// state the point changes nothing but rounding.
///
/// Only the EKF's pictures relinearise, so both are defined in relinearised_increment_impl.hpp
/// and compiled once per state size of such a picture (picture/state_size_code.hpp); this header
/// declares them.

#include "skyfuse/core/types.hpp"
#include "skyfuse/fusion/station_observation.hpp"

namespace skyfuse {

/// The point at which observation `o` of a track of prior `prior` is linearised after `times`
/// steps of the iteration above (0: the prior mean). A step whose innovation covariance does not
/// factor stops the iteration where it stands.
template <int N, typename Sensor>
Vector<N> relinearised_point(const GaussianState<N>& prior, const StationObservation<Sensor>& o,
                             int times);

/// `prior` with its mean moved to observation `o`'s linearisation point after `times` steps:
/// what an increment rule takes as the prior so that its H, h and dy are the relinearised ones
/// (the covariance is not read by the increment; it stays the prior's).
template <int N, typename Sensor>
GaussianState<N> relinearised_prior(const GaussianState<N>& prior,
                                    const StationObservation<Sensor>& o, int times);

}  // namespace skyfuse
