#pragma once
// The harness's side of a lock-step run over DDS: waits until every station and the center
// have joined, then for each step publishes Tick{run, k} and waits for every process's track of
// step k (and every station's measurement, which the harness records). The harness adds no
// estimation; it only observes.

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::harness {

/// A run was abandoned: a child died, a node reported failure, time ran out, or the user
/// interrupted. The message says which.
class RunAborted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RoundRecord {
  std::uint64_t step = 0;
  GaussianState<9> central;
  std::vector<GaussianState<9>> peers;  ///< ascending station id
  std::vector<Vector3> measurements;    ///< ascending station id
  std::chrono::nanoseconds latency{0};  ///< tick published -> last track received
  /// Real time only: age of each track on arrival (scheduled step start -> received), the center
  /// first then the stations in ascending id; and whether every node fused all M inputs.
  std::vector<double> track_age_us;
  bool all_inputs_in_time = true;
};

/// The harness's key among node ids in drop counts.
inline constexpr int kHarnessNodeId = -1;

class LockstepDriver {
 public:
  /// `check` is called at least every 50 ms while waiting; it throws RunAborted to end the run.
  LockstepDriver(const transport::NodeConfig& config, std::uint64_t run_id,
                 std::vector<int> station_ids, std::function<void()> check);
  ~LockstepDriver();

  /// Waits until every station and the center have announced READY and the harness's own
  /// endpoints match them. Returns the time it took.
  std::chrono::nanoseconds wait_until_joined(std::chrono::milliseconds timeout);

  /// Runs step k and returns what every process published for it.
  RoundRecord run_round(std::uint64_t k, std::chrono::milliseconds timeout);

  /// Real-time mode: publishes the start tick (step 0 begins at `epoch`) and gathers every
  /// node's track of every step as the nodes publish them on their own clocks.
  std::vector<RoundRecord> run_realtime(int steps, double time_step_s,
                                        std::chrono::system_clock::time_point epoch,
                                        std::chrono::milliseconds timeout);

  /// Drop counts of every node that has announced FINISHED so far, by node id (0: center),
  /// and the harness's own under kHarnessNodeId.
  std::map<int, DropCounts> finished_drops();

  /// Tells every process to stop (a Tick with stop = true).
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace skyfuse::harness
