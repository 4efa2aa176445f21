#include <array>

#include "skyfuse/asterix/quality.hpp"

namespace skyfuse::asterix {
namespace {

constexpr double kNauticalMileM = 1852.0;

// NACp 1..11's bounds on the 95 % horizontal position error (DO-260B 2.2.3.2.7.2.7).
constexpr std::array<double, 11> kEpuM{10.0 * kNauticalMileM,
                                       4.0 * kNauticalMileM,
                                       2.0 * kNauticalMileM,
                                       1.0 * kNauticalMileM,
                                       0.5 * kNauticalMileM,
                                       0.3 * kNauticalMileM,
                                       0.1 * kNauticalMileM,
                                       0.05 * kNauticalMileM,
                                       30.0,
                                       10.0,
                                       3.0};
// NACv 1..4's bounds on the 95 % horizontal velocity error (DO-260B 2.2.3.2.6.1.5).
constexpr std::array<double, 4> kVelocityErrorMps{10.0, 3.0, 1.0, 0.3};

template <std::size_t N>
std::uint8_t best_category(const std::array<double, N>& bounds, double error) {
  std::uint8_t category = 0;
  for (std::size_t i = 0; i < N; ++i) {
    if (error < bounds[i]) category = static_cast<std::uint8_t>(i + 1);
  }
  return category;
}

}  // namespace

std::uint8_t nacp_of_epu(double epu_m) {
  return best_category(kEpuM, epu_m);
}

std::optional<double> epu_of_nacp(std::uint8_t nacp) {
  if (nacp == 0 || nacp > kEpuM.size()) return std::nullopt;
  return kEpuM[nacp - 1U];
}

std::uint8_t nacv_of_error(double error_mps) {
  return best_category(kVelocityErrorMps, error_mps);
}

std::optional<double> error_of_nacv(std::uint8_t nacv) {
  if (nacv == 0 || nacv > kVelocityErrorMps.size()) return std::nullopt;
  return kVelocityErrorMps[nacv - 1U];
}

}  // namespace skyfuse::asterix
