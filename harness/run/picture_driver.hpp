#pragma once
// The harness's side of a run of many aircraft over DDS: every node's picture
// (wire::PictureRound) in, the ticks and statuses through its NodeRoster. Lock-step: one tick per
// round, the round handed over once every node that is up has published its picture. Real time: one
// start tick, the nodes run on their own clocks, and each round is handed over once every node's
// picture is in or it is late.

#include <chrono>
#include <cstdint>
#include <functional>
#include <vector>

#include "run/node_roster.hpp"
#include "skyfuse/transport/dds_node.hpp"

namespace skyfuse::harness {

class PictureDriver final {
 public:
  /// `ids`: the nodes, ascending (the center, 0, first). `stop_check` is called at least every
  /// 50 ms while waiting; it throws RunAborted to end the run (a signal, a failed node).
  PictureDriver(const transport::NodeConfig& config, std::uint64_t run_id, std::vector<int> ids,
                std::function<void()> stop_check);

  /// The nodes' statuses, the ticks, joining, kills and restarts.
  NodeRoster& roster() { return roster_; }

  /// Lock-step round k: its tick, then every node's picture of step k (node order), within
  /// `timeout` (RunAborted otherwise).
  std::vector<wire::PictureRound> run_round(std::uint32_t k, std::chrono::milliseconds timeout);

  /// Real time: the start tick (step 0 begins at `epoch`), then each of the `steps` rounds
  /// handed to `on_round` in step order with the pictures that came (node order), once every
  /// node's is in or `late_after` has passed since the round's scheduled end.
  void run_realtime(int steps, double time_step_s, std::chrono::system_clock::time_point epoch,
                    std::chrono::milliseconds late_after,
                    const std::function<void(int, std::vector<wire::PictureRound>)>& on_round);

 private:
  std::uint64_t run_id_;
  std::vector<int> ids_;  // ascending
  NodeRoster roster_;
  transport::Reader<wire::PictureRound> rounds_;
};

}  // namespace skyfuse::harness
