#include "skyfuse/random/link_loss.hpp"

#include "skyfuse/random/counter_rng.hpp"

namespace skyfuse {

bool LinkLoss::lost(int receiver, int sender, std::uint64_t step) const {
  if (!enabled() || step < first_step || step >= end_step || receiver == sender) return false;
  // One key per directed link and step: (receiver, sender) packed into the station word.
  const std::uint64_t link =
      (static_cast<std::uint64_t>(static_cast<std::uint32_t>(receiver)) << 32) |
      static_cast<std::uint32_t>(sender);
  CounterRng rng(NoiseKey{seed, 0, link, step, NoiseStream::kLinkLoss});
  return rng.uniform() < probability;
}

}  // namespace skyfuse
