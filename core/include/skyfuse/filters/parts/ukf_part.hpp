#pragma once
/// \file
/// Filter kind "ukf" as a registered part: the unscented information filter. Each station
/// regresses its sensor on the state over the sigma points of the common prior and sends the
/// increment H~^T R^-1 H~, H~^T R^-1 (nu + H~ x^) (filters/unscented.hpp, with alpha = 1,
/// beta = 2, kappa = 0); peers sum the increments as the EKF's. The center computes the same
/// increments from the raw measurements and sums them onto its own prior: the unscented filter
/// on the stacked measurement, whose regression is the stack of the stations'.
///
/// It runs on any registered model with stations of one sensor kind and takes every option: a
/// fixed-lag re-fusion, and a NIS gate on the unscented innovation covariance P_zz + R. Its
/// rule (tracking/unscented_increment_rule.hpp) is all the station, the center and the
/// in-process twin need of it; the center also reports how far the covariance-form UKF on the
/// stacked measurement lies from its update.

#include <array>
#include <string_view>

namespace skyfuse {

struct UnscentedIncrementRule;  // tracking/unscented_increment_rule.hpp

struct UkfFilterPart {
  static constexpr std::string_view kKind = "ukf";
  static constexpr std::string_view kSummary =
      "unscented information filter: statistically linearised increments, summed like the EKF's";
  static constexpr std::string_view kMotionModel = {};
  static constexpr std::string_view kSensor = {};
  static constexpr bool kOneSensorKind = true;
  static constexpr bool kTakesRefusionLag = true;
  static constexpr bool kTakesNisGate = true;
  static constexpr std::array<std::string_view, 0> kModeNames = {};
  static constexpr int kNeesDof = 0;
  // Its station processes run the tree exchange (stations/tree_exchange.hpp).
  static constexpr bool kNodesTakeTree = true;
  using IncrementRule = UnscentedIncrementRule;
};

}  // namespace skyfuse
