#pragma once
// The parts of a scenario with many aircraft, read from its YAML (scenario_loader.cpp calls
// these): `traffic:`, `detection:` (the scenario's and a station's own), `tracker:`,
// `metrics:`.

#include <span>
#include <string_view>

#include "scenario/yaml_field.hpp"
#include "skyfuse/scenario/traffic_config.hpp"

namespace skyfuse::detail {

/// A one-target scenario's `target:`, with `also_allowed` keys left for the caller.
TargetConfig read_target(const YamlField& field, std::span<const std::string_view> also_allowed);

/// `detection:` over `defaults` (a station's over the scenario's).
DetectionConfig read_detection(const YamlField& field, const DetectionConfig& defaults);

/// The scenario's `traffic:`, with its optional `detection:` and `metrics:`.
TrafficConfig read_traffic(const YamlField& traffic, const std::optional<YamlField>& detection,
                           const std::optional<YamlField>& metrics);

/// The scenario's `tracker:`.
TrackerConfig read_tracker(const YamlField& field);

}  // namespace skyfuse::detail
