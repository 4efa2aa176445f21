#pragma once
/// \file
/// What each station's scan shows a person at a step of a run with many aircraft: every
/// detection as the position it fixes (the sensor's inverse), and which aircraft it came from or
/// that it is a false alarm. The same scans, bit for bit, as the stations simulate (a scan is a
/// function of seed, run, station and step), so that a recording of a run over DDS draws what
/// its stations associated without the harness hearing their scans.

#include <cstdint>
#include <string_view>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/traffic/target_truth.hpp"

namespace skyfuse {

struct ScanPositions {
  int station_id = 0;
  std::vector<Vector3> positions;  ///< in the scan's (shuffled) order
  std::vector<int> target;         ///< per detection: the aircraft's index, or -1 for clutter
};

/// The scans of the first `stations` stations of `scenario` (a run with many aircraft, whose
/// stations' sensor fixes a position) at step `step` of Monte-Carlo run `run`.
std::vector<ScanPositions> scan_positions_at(const Scenario& scenario,
                                             const std::vector<TargetTruth>& truth, int stations,
                                             std::uint64_t run, int step);

/// A station's scan as it simulates it: its sensor's kind (as a scenario names it), its
/// detections with their addresses, and which aircraft each came from (-1: a false alarm).
struct SimulatedScan {
  std::string_view sensor_kind;
  Scan scan;
  std::vector<int> target;
};

/// The same scans as scan_positions_at's, as the stations hold them.
std::vector<SimulatedScan> simulated_scans_at(const Scenario& scenario,
                                              const std::vector<TargetTruth>& truth, int stations,
                                              std::uint64_t run, int step);

}  // namespace skyfuse
