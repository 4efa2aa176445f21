#pragma once
/// \file
/// A track's height no less known than the band its 2-D radars assume (models/height_band.hpp).
/// A 2-D radar measures no height. A track that only 2-D radars see learns little of it from
/// their slant ranges, and without a bound its height's variance grows with the process noise
/// round after round, until the covariance is so ill-conditioned that the peers' information
/// form and the center's covariance form round apart (docs/picture.md, "A 2-D radar").
///
/// The bound: where a track's height variance exceeds the band's, V (a height uniform over the
/// band), the track is conditioned on a pseudo-measurement of the band's middle whose variance
/// R = P V / (P − V) leaves exactly V — "somewhere in the band", as 2-D trackers assume an
/// altitude. It is a Kalman update of the height alone, so the other entries move with their
/// correlation to it. A track whose height something measures (P ≤ V) is left as it is, bit for
/// bit. Every node applies it to its own picture at the close of a round, as it manages tracks.

#include <optional>
#include <span>
#include <tuple>
#include <variant>

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/height_band.hpp"
#include "skyfuse/picture/known_station.hpp"

namespace skyfuse {

/// The heights `stations`' 2-D radars assume: the smallest band holding every one's; nullopt
/// where none assumes a height.
template <int N>
std::optional<HeightBand> assumed_height_band(std::span<const KnownStation<N>> stations) {
  std::optional<HeightBand> band;
  for (const KnownStation<N>& station : stations) {
    std::visit(
        [&]<typename Sensor>(const Sensor& sensor) {
          if constexpr (TakesHeightBand<Sensor>) {
            const HeightBand own = sensor.height_band();
            if (!band) {
              band = own;
            } else {
              band->low_m = std::min(band->low_m, own.low_m);
              band->high_m = std::max(band->high_m, own.high_m);
            }
          }
        },
        station.sensor);
  }
  return band;
}

/// `state` (its height the third entry) bound by `band`; whether it changed.
template <int N>
bool bound_height(GaussianState<N>& state, const HeightBand& band) {
  constexpr int kHeight = 2;
  const double p = state.covariance(kHeight, kHeight);
  const double v = band.variance_m2();
  if (!(p > v)) return false;
  // Gain of a pseudo-measurement of variance r = p v / (p - v): P e / (p + r) = P e (p - v) / p².
  const Vector<N> gain = state.covariance.col(kHeight) * ((p - v) / (p * p));
  state.mean += gain * (band.middle_m() - state.mean(kHeight));
  const Covariance<N> taken = gain * state.covariance.row(kHeight);
  state.covariance -= taken;
  symmetrize(state.covariance);
  return true;
}

/// An IMM track's modes, each bound alike; the mode probabilities are kept (the pseudo-
/// measurement is one every mode takes, not evidence for one mode over another).
template <typename ImmState>
requires requires(const ImmState& s) {
  s.filter().mode_states();
}
bool bound_height(ImmState& state, const HeightBand& band) {
  // Most rounds no mode's height is looser than the band: nothing is copied then.
  const auto loose = [&](const auto&... mode) {
    return ((mode.covariance(2, 2) > band.variance_m2()) || ...);
  };
  if (!std::apply(loose, state.filter().mode_states())) return false;
  auto modes = state.filter().mode_states();
  std::apply([&](auto&... mode) { (bound_height(mode, band), ...); }, modes);
  state.restore(modes, state.filter().mode_probabilities());
  return true;
}

}  // namespace skyfuse
