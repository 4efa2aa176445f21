#pragma once
// What the harness records of one step: every node's track and every station's measurement,
// as received, with their timing. Plain data, no DDS.

#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::harness {

/// The center's node id (stations are numbered from 1).
inline constexpr int kCenterNodeId = 0;

/// A node's track as received: the estimate (of the run's state dimension) and the stations
/// fused into it.
struct ReceivedTrack {
  DynamicGaussianState estimate;
  std::vector<int> contributors;  ///< ascending station id
  /// An IMM run's mode probabilities (the scenario's filter.imm.modes order); empty otherwise.
  Eigen::VectorXd mode_probabilities;
};

/// Samples a node reported refusing: `count` of one kind, in rounds up to its round `step`.
struct Refusal {
  int node = 0;  ///< kCenterNodeId, a station id, or the harness (-1)
  std::uint64_t step = 0;
  DropKind kind = DropKind::kWrongRun;
  std::uint64_t count = 0;
};

struct RoundRecord {
  std::uint64_t step = 0;
  /// Each empty when the node delivered nothing for the step (down, or past the deadline).
  std::optional<ReceivedTrack> central;
  std::vector<std::optional<ReceivedTrack>> peers;  ///< ascending station id
  /// Each station's measurement, in its sensor's components; ascending station id.
  std::vector<std::optional<Eigen::VectorXd>> measurements;
  std::chrono::nanoseconds latency{0};  ///< tick published -> last track received
  /// Real time only: age of each track on arrival (scheduled step start -> received), the center
  /// first then the stations in ascending id; and whether every node fused all M inputs.
  std::vector<double> track_age_us;
  bool all_inputs_in_time = true;
  /// Refusals reported while this round was collected (a node reports after its round, so
  /// usually this round's or the one before), by node and kind.
  std::vector<Refusal> refused;
};

}  // namespace skyfuse::harness
