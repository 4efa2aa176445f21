#pragma once
/// \file
/// Simulated delay on the links of the fusion network (`skyfuse run --link-delay-ms D
/// --link-jitter-ms J`): the sample a sender publishes for a step reaches one receiver D + J u
/// milliseconds after it arrived, u uniform in [-1, 1], never less than 0. The delay is a pure
/// function of (seed, receiver, sender, step), so a rerun delays the same samples by the same
/// amounts, and different links reorder their samples. Kernels here have no `netem` qdisc, so
/// the delay is applied where the samples are received, as the simulated loss is.

#include <chrono>
#include <cstdint>

namespace skyfuse {

struct LinkDelay {
  double delay_ms = 0.0;   ///< D, >= 0
  double jitter_ms = 0.0;  ///< J, >= 0

  bool enabled() const { return delay_ms > 0.0 || jitter_ms > 0.0; }
  /// How long `sender`'s sample of `step` is held at `receiver` (0: the fusion center); zero
  /// for a node's own samples.
  std::chrono::microseconds of(std::uint64_t seed, int receiver, int sender,
                               std::uint64_t step) const;
};

}  // namespace skyfuse
