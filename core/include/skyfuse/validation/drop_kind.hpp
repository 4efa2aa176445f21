#pragma once
/// \file
/// Why a received sample was not fused. Every receiver (station, center, harness) counts its
/// drops by kind; the counts travel in the status topic and end in summary.json.
///
/// There is no "not symmetric" kind: every symmetric matrix (dQ, R, P) travels as its upper
/// triangle, so an asymmetric one cannot be expressed on the wire.

#include <array>
#include <cstdint>
#include <string_view>

namespace skyfuse {

enum class DropKind : std::uint8_t {
  kWrongRun,        ///< run id of another run
  kStaleStep,       ///< a step already closed
  kFutureStep,      ///< a step more than one ahead
  kUnknownStation,  ///< station id not among the participants
  kDuplicate,       ///< a second sample for (step, station), or one from another process
  kNonFinite,       ///< NaN or Inf anywhere
  kNotPositive,     ///< dQ not positive semi-definite, or R not positive definite
  kOutOfRange,      ///< a measurement outside what the sensor can report
  kNisGate,         ///< innovation beyond the chi-square gate
  kWrongSite,       ///< a measurement whose station position is not the scenario's for that id
  kWrongCluster,    ///< a tree exchange's sum counting a station outside its cluster
  kOverlap,         ///< a tree exchange's sum counting a station twice, or one already counted
};
inline constexpr std::size_t kDropKinds = 12;

/// snake_case name, as used in logs and in summary.json.
constexpr std::string_view to_string(DropKind kind) {
  constexpr std::array<std::string_view, kDropKinds> kNames = {
      "wrong_run", "stale_step", "future_step",   "unknown_station",
      "duplicate", "non_finite", "not_positive",  "out_of_range",
      "nis_gate",  "wrong_site", "wrong_cluster", "overlap"};
  return kNames[static_cast<std::size_t>(kind)];
}

/// Counts per kind, indexed by the enum.
using DropCounts = std::array<std::uint64_t, kDropKinds>;

}  // namespace skyfuse
