#include "skyfuse/asterix/quantity.hpp"

#include <cmath>

namespace skyfuse::asterix {
namespace {

struct FieldRange {
  std::int64_t min;
  std::int64_t max;
};

FieldRange range_of(unsigned bits, Signedness signedness) {
  if (signedness == Signedness::unsigned_field) return {0, (std::int64_t{1} << bits) - 1};
  return {-(std::int64_t{1} << (bits - 1)), (std::int64_t{1} << (bits - 1)) - 1};
}

// The nearest count, or nullopt when value/lsb is not finite or too large for llround (the
// fields are at most 32 bits, so anything beyond 2^40 is out of range anyway).
std::optional<std::int64_t> nearest_count(double value, double lsb) {
  const double counts = value / lsb;
  if (!std::isfinite(counts) || std::fabs(counts) > 1e12) return std::nullopt;
  return static_cast<std::int64_t>(std::llround(counts));
}

}  // namespace

std::optional<std::int64_t> quantise(double value, double lsb, unsigned bits,
                                     Signedness signedness) {
  if (bits == 0 || bits > 32 || !(lsb > 0.0)) return std::nullopt;
  const auto count = nearest_count(value, lsb);
  if (!count) return std::nullopt;
  const auto range = range_of(bits, signedness);
  if (*count < range.min || *count > range.max) return std::nullopt;
  return count;
}

std::optional<std::int64_t> quantise_clamped(double value, double lsb, unsigned bits) {
  if (bits == 0 || bits > 32 || !(lsb > 0.0) || std::isnan(value) || value < 0.0) {
    return std::nullopt;
  }
  const std::int64_t max = (std::int64_t{1} << bits) - 1;
  const auto count = nearest_count(value, lsb);
  if (!count) return max;  // +inf or beyond 2^40 LSBs: "maximum value or above"
  return *count > max ? max : *count;
}

std::uint32_t field_bits(std::int64_t count, unsigned bits) {
  const std::uint64_t mask = (std::uint64_t{1} << bits) - 1;
  return static_cast<std::uint32_t>(static_cast<std::uint64_t>(count) & mask);
}

std::int64_t sign_extend(std::uint32_t raw, unsigned bits) {
  const std::uint64_t mask = (std::uint64_t{1} << bits) - 1;
  const std::uint64_t value = raw & mask;
  const std::uint64_t sign = std::uint64_t{1} << (bits - 1);
  return (value & sign) != 0
             ? static_cast<std::int64_t>(value) - static_cast<std::int64_t>(mask) - 1
             : static_cast<std::int64_t>(value);
}

}  // namespace skyfuse::asterix
