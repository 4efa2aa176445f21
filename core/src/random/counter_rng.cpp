#include "skyfuse/random/counter_rng.hpp"

#include <cmath>
#include <numbers>

namespace skyfuse {
namespace {

constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ULL;

// SplitMix64 finaliser: a bijective mix whose outputs pass BigCrush when fed a counter.
std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t absorb(std::uint64_t hash, std::uint64_t word) {
  return mix(hash + kGolden + word);
}

}  // namespace

CounterRng::CounterRng(const NoiseKey& key) {
  std::uint64_t h = mix(key.seed);
  h = absorb(h, key.run);
  h = absorb(h, key.station);
  h = absorb(h, key.step);
  h = absorb(h, static_cast<std::uint64_t>(key.stream));
  if (key.target != 0) h = absorb(h, key.target);
  state_ = h;
}

std::uint64_t CounterRng::next_u64() {
  state_ += kGolden;
  return mix(state_);
}

double CounterRng::uniform() {
  // 53 random bits, shifted by half an ulp so that 0 cannot occur.
  return (static_cast<double>(next_u64() >> 11) + 0.5) * 0x1.0p-53;
}

double CounterRng::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_normal_;
  }
  const double radius = std::sqrt(-2.0 * std::log(uniform()));
  const double angle = 2.0 * std::numbers::pi * uniform();
  spare_normal_ = radius * std::sin(angle);
  has_spare_ = true;
  return radius * std::cos(angle);
}

}  // namespace skyfuse
