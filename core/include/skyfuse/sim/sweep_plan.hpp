#pragma once
/// \file
/// What a sweep is (`skyfuse sweep`): Monte-Carlo runs, in-process, of a scenario after its
/// overrides. Its kind is the scenario's (sim/run_kind.hpp), as make_plan (sim/any_plan.hpp)
/// decides a run's: one aircraft sweeps every speed the scenario lists over M = 1..max stations
/// (a run's plan fixes one speed and one M, so a sweep is no RunPlan); many aircraft run their
/// picture with the first max stations. An override the kind does not take is refused by name.

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

struct SweepOverrides {
  std::optional<std::uint64_t> seed;             ///< default: the scenario's
  std::optional<int> steps;                      ///< default: the scenario's
  std::optional<ExchangeConfig::Kind> exchange;  ///< default: the scenario's
  std::optional<int> fanout;                     ///< default: the scenario's
  std::optional<std::string> associator;         ///< many aircraft; default: the scenario's
  /// Only the scenario's stations of these ids, in its order; empty: every one.
  std::vector<int> only_stations;
  std::optional<int> max_stations;  ///< default: every station (after only_stations)
  /// Recorded traffic: the OpenSky CSV to fly instead of the scenario's; empty: the scenario's.
  std::string traffic_file;
};

/// One aircraft: every speed the scenario lists, over M = 1..max_stations.
struct OneAircraftSweep {
  Scenario scenario;
  int max_stations = 0;
};

/// Many aircraft: their picture with the scenario's first `stations` stations, flying the
/// scenario's traffic (or `traffic_file`'s recording).
struct PictureSweep {
  Scenario scenario;
  int stations = 0;
  std::string traffic_file;
};

using SweepPlan = std::variant<OneAircraftSweep, PictureSweep>;

/// The sweep of `scenario` with `overrides`, of the kind the scenario is; throws
/// std::invalid_argument naming the option for an override out of range or one the kind does
/// not take (a traffic file for one aircraft).
SweepPlan make_sweep_plan(Scenario scenario, const SweepOverrides& overrides);

}  // namespace skyfuse
