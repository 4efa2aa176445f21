#pragma once
/// \file
/// Filter kind "imm" as a registered part: the station network's IMM of 3-D constant velocity,
/// the scenario's constant-acceleration model and a coordinated turn (tracking/imm_network.hpp,
/// scenario.hpp's ImmConfig). Each station sends one increment per mode against that mode's
/// prior, with the scalars that give every peer the exact stacked mode likelihood; the center
/// runs every mode on the stacked measurement.
///
/// Its modes take the stations' sensor at their own dimension, so a run has one sensor kind.
/// It fuses each round once: no fixed-lag re-fusion yet. Its NEES is of [p; v], the six
/// entries every mode shares.

#include <string_view>

#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

struct ImmFilterPart {
  static constexpr std::string_view kKind = "imm";
  static constexpr std::string_view kSummary =
      "IMM of CV, CA and CT modes: per-mode increments and the exact stacked likelihood";
  static constexpr std::string_view kMotionModel = "constant_acceleration_3d";  // its CA mode
  static constexpr std::string_view kSensor = {};
  static constexpr bool kOneSensorKind = true;
  static constexpr bool kTakesRefusionLag = false;
  static constexpr bool kTakesNisGate = true;
  static constexpr auto kModeNames = ImmConfig::kModeNames;
  static constexpr int kNeesDof = 6;
};

}  // namespace skyfuse
