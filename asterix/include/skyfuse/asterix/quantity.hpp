#pragma once
// Physical values as ASTERIX carries them: an integer count of the item's LSB in a field of a
// given number of bits, unsigned or two's complement.
//
// Rounding: to the nearest count, ties away from zero (std::llround), so a value is carried
// within half an LSB. Range: a count the field cannot hold is refused (std::nullopt), never
// wrapped and never clamped; so is a value that is not finite. The one place the standard
// itself asks for clamping (I062/500: "maximum value means maximum value or above") calls
// quantise_clamped explicitly.

#include <cstdint>
#include <optional>

namespace skyfuse::asterix {

enum class Signedness : std::uint8_t { unsigned_field, twos_complement };

/// The count of `lsb` nearest to `value` if a field of `bits` (1..32) of `signedness` holds
/// it; std::nullopt if not, or if `value` is not finite.
std::optional<std::int64_t> quantise(double value, double lsb, unsigned bits,
                                     Signedness signedness);

/// As quantise, but a count above the field's maximum becomes the maximum (the standard's "or
/// above" items). A negative value, or one that is not finite, is still refused.
std::optional<std::int64_t> quantise_clamped(double value, double lsb, unsigned bits);

/// The field's bits of `count` (its two's complement for a negative count), right-aligned.
std::uint32_t field_bits(std::int64_t count, unsigned bits);

/// The count a field of `bits` holds, read as two's complement.
std::int64_t sign_extend(std::uint32_t raw, unsigned bits);

}  // namespace skyfuse::asterix
