#pragma once
/// \file
/// Simulated loss on the links of the fusion network (`skyfuse run --loss P`): the sample a
/// sender publishes for a step is lost on its way to one receiver with probability P, within a
/// window of steps. Whether it is lost is a pure function of (seed, receiver, sender, step), so
/// a rerun loses the same samples whatever the timing, and every receiver draws for itself.

#include <cstdint>
#include <limits>

namespace skyfuse {

struct LinkLoss {
  double probability = 0.0;  ///< in [0, 1]
  std::uint64_t first_step = 0;
  std::uint64_t end_step = std::numeric_limits<std::uint64_t>::max();  ///< exclusive
  std::uint64_t seed = 1;

  bool enabled() const { return probability > 0.0 && first_step < end_step; }
  /// Whether `sender`'s sample of `step` never reaches `receiver` (0: the fusion center).
  bool lost(int receiver, int sender, std::uint64_t step) const;
};

}  // namespace skyfuse
