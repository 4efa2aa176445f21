#pragma once
/// \file
/// Filter kind "ncrkf" as a registered part: paper 002's noise-correlation robust Kalman filter
/// run by a network of TDOA receivers (tracking/tdoa_round.hpp). Each receiver publishes its
/// bias-compensated pseudo-linear increment, which depends on its measurement and site only;
/// the center computes the same increments from the raw measurements and fuses them alike.
///
/// It runs on paper 002's relative motion model with range-difference receivers only, and its
/// increments have no innovation, so it takes no NIS gate.

#include <array>
#include <string_view>

namespace skyfuse {

struct NcrkfFilterPart {
  static constexpr std::string_view kKind = "ncrkf";
  static constexpr std::string_view kSummary =
      "paper 002's noise-correlation robust KF on TDOA receivers: bias-compensated increments";
  static constexpr std::string_view kMotionModel = "tdoa_relative_constant_acceleration";
  static constexpr std::string_view kSensor = "tdoa_range_difference";
  static constexpr bool kOneSensorKind = true;
  static constexpr bool kTakesRefusionLag = true;
  static constexpr bool kTakesNisGate = false;
  static constexpr std::array<std::string_view, 0> kModeNames = {};
  static constexpr int kNeesDof = 0;
  // Its station processes run the tree exchange, each sum with its fallback without the
  // indefinite increments (tracking/tdoa_partial_sum.hpp).
  static constexpr bool kNodesTakeTree = true;
};

}  // namespace skyfuse
