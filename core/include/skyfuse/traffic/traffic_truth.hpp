#pragma once
/// \file
/// The truth of a scenario with many aircraft, from whatever its `traffic:` names: its list of
/// targets, the generator's aircraft, a recorded file's flights — together, in that order.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/traffic/recorded_traffic.hpp"
#include "skyfuse/traffic/target_truth.hpp"

namespace skyfuse {

struct TrafficTruth {
  std::vector<TargetTruth> targets;
  /// What the recorded file gave, if the scenario has one (rows read and skipped, by why).
  std::optional<RecordedTraffic> recorded;
};

/// The aircraft of `scenario` (one with 'traffic') over its steps 0..steps. A recorded
/// file is read from `recorded_file` if given, otherwise from the scenario's own, relative to
/// the scenario file. The generator's aircraft are the same in every Monte-Carlo run: a
/// function of the scenario's seed.
TrafficTruth build_traffic_truth(const Scenario& scenario, const std::string& recorded_file = {});

/// The recorded file build_traffic_truth reads: `recorded_file` if given, otherwise the
/// scenario's own, relative to the scenario file; none if the scenario records no traffic.
std::optional<std::filesystem::path> recorded_traffic_file(const Scenario& scenario,
                                                           const std::string& recorded_file = {});

}  // namespace skyfuse
