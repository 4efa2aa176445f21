#pragma once
/// \file
/// Filter kind "ekf" as a registered part: the extended Kalman filter, which is the Kalman
/// filter itself when the model and sensor are linear. Every station turns its measurement into
/// an information increment H^T R^-1 H, H^T R^-1 (nu + H x-) against the common prior; the
/// center stacks the raw measurements into one update (fusion/stacked_ekf.hpp). It runs on any
/// registered model and sensor, mixed or not, and takes every option.

#include <array>
#include <string_view>

namespace skyfuse {

struct EkfIncrementRule;  // tracking/ekf_increment_rule.hpp

struct EkfFilterPart {
  static constexpr std::string_view kKind = "ekf";
  static constexpr std::string_view kSummary =
      "extended Kalman filter: stations exchange information increments, the center stacks";
  static constexpr std::string_view kMotionModel = {};  // any
  static constexpr std::string_view kSensor = {};       // any, mixed or not
  static constexpr bool kOneSensorKind = false;
  static constexpr bool kTakesRefusionLag = true;
  static constexpr bool kTakesNisGate = true;
  static constexpr std::array<std::string_view, 0> kModeNames = {};
  static constexpr int kNeesDof = 0;  // the model's state
  // Its station processes run the tree exchange (stations/tree_exchange.hpp).
  static constexpr bool kNodesTakeTree = true;
  /// A station's increment. (The center stacks the raw measurements instead: its own line in
  /// fusion_center/central_fusion.hpp and core/src/sim/run_steppers.hpp.)
  using IncrementRule = EkfIncrementRule;
};

}  // namespace skyfuse
