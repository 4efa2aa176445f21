#pragma once
/// \file
/// Filter kind "imm" as a registered part: the station network's IMM of the modes `Modes` (an
/// ImmModeSet, tracking/imm_modes.hpp), one part per set the registry lists; the scenario picks
/// one by filter.imm.modes. Each station sends one increment per mode against that mode's
/// prior, with the scalars that give every peer the exact stacked mode likelihood; the center
/// runs every mode on the stacked measurement (tracking/imm_network.hpp).
///
/// Its modes take the stations' sensor at their own dimension, so a run has one sensor kind.
/// It fuses each round once: no fixed-lag re-fusion yet. Its NEES is of [p; v], the six
/// entries every mode shares. The scenario's motion model gives the initial estimate's
/// [p; v; a] and P0, and its process noise is the CA mode's when the set has one.

#include <string_view>

#include "skyfuse/tracking/imm_modes.hpp"

namespace skyfuse {

template <typename Modes>
struct ImmFilterPart {
  using ModeSet = Modes;
  static constexpr std::string_view kKind = "imm";
  static constexpr std::string_view kSummary =
      "IMM of the scenario's modes: per-mode increments and the exact stacked likelihood";
  static constexpr std::string_view kMotionModel = ConstantAcceleration3D::kKind;
  static constexpr std::string_view kSensor = {};
  static constexpr bool kOneSensorKind = true;
  static constexpr bool kTakesRefusionLag = false;
  static constexpr bool kTakesNisGate = true;
  static constexpr auto kModeNames = Modes::kNames;
  static constexpr int kNeesDof = 6;
  // Its station processes run the tree exchange, every mode summed (tracking/imm_partial_sum.hpp).
  static constexpr bool kNodesTakeTree = true;
};

}  // namespace skyfuse
