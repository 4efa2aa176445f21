#pragma once
/// \file
/// What a scenario with many aircraft adds of the world (its `traffic:`, `detection:` and
/// `metrics:`; see scenarios/uam-city.yaml; its `tracker:` is Scenario::tracker). Plain data: the
/// loader reads it (scenario/traffic_reader.cpp), traffic/traffic_truth.hpp turns it into truth.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "skyfuse/metrics/gospa.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/traffic/detection_model.hpp"

namespace skyfuse {

/// One aircraft of a scenario's list: its path (as a one-target scenario's target, flown at its
/// first speed) and when it is in the air.
struct ScheduledTarget {
  TargetConfig path;
  double appears_s = 0.0;
  std::optional<double> leaves_s;  ///< none: until the run ends
};

/// N aircraft over an area, seeded by the scenario's seed: straight legs joined by turns at
/// UAM speeds and heights. Each [low, high] is drawn uniformly per aircraft (per leg, per turn).
struct TrafficGeneratorConfig {
  int aircraft = 0;
  std::array<double, 2> east_m{-5000.0, 5000.0};
  std::array<double, 2> north_m{-5000.0, 5000.0};
  std::array<double, 2> height_m{100.0, 600.0};
  std::array<double, 2> speed_mps{15.0, 60.0};
  std::array<double, 2> leg_s{30.0, 120.0};
  std::array<double, 2> turn_deg{30.0, 120.0};  ///< heading change of a turn
  std::array<double, 2> turn_rate_deg_s{2.0, 6.0};
  double appear_within_s = 0.0;  ///< each aircraft appears at a uniform time in [0, this]
};

/// Truth from an OpenSky state-vector CSV file a user downloaded (traffic/recorded_traffic.hpp).
struct RecordedTrafficConfig {
  std::string file;  ///< relative to the scenario file; `skyfuse sweep --traffic-file` overrides
  std::optional<double> start_time_s;  ///< Unix time of step 0; none: the file's first
  double max_staleness_s = 15.0;
};

struct TrafficConfig {
  /// The bounds a scenario may not exceed: beyond them a round's work is no longer bounded.
  static constexpr int kMaxAircraft = 10000;

  std::vector<ScheduledTarget> targets;
  std::optional<TrafficGeneratorConfig> generator;
  std::optional<RecordedTrafficConfig> recorded;
  /// Every station's, unless the station gives its own (the loader resolves each station's
  /// into StationConfig::detection).
  DetectionConfig detection;
  /// The share of aircraft that carry a transponder or a broadcast (an address), each drawn
  /// from the scenario's seed; a recorded aircraft's address is its ICAO 24-bit address.
  double equipped_share = 1.0;
  GospaParameters gospa{.cutoff_m = 50.0, .order = 2.0};
};

}  // namespace skyfuse
