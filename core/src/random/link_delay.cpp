#include "skyfuse/random/link_delay.hpp"

#include <algorithm>
#include <cmath>

#include "skyfuse/random/counter_rng.hpp"

namespace skyfuse {

std::chrono::microseconds LinkDelay::of(std::uint64_t seed, int receiver, int sender,
                                        std::uint64_t step) const {
  if (!enabled() || receiver == sender) return std::chrono::microseconds(0);
  // One key per directed link and step, as for the loss, on a stream of its own.
  const std::uint64_t link =
      (static_cast<std::uint64_t>(static_cast<std::uint32_t>(receiver)) << 32) |
      static_cast<std::uint32_t>(sender);
  CounterRng rng(NoiseKey{seed, 0, link, step, NoiseStream::kLinkDelay});
  const double ms = std::max(0.0, delay_ms + jitter_ms * (2.0 * rng.uniform() - 1.0));
  return std::chrono::microseconds(std::llround(ms * 1000.0));
}

}  // namespace skyfuse
