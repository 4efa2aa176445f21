#pragma once
// The harness's side of a run of many aircraft over DDS: ticks out, every node's picture
// (wire::PictureRound) and statuses in. Lock-step: one tick per round, the round handed over
// once every node that is up has published its picture. Real time: one start tick, the nodes
// run on their own clocks, and each round is handed over once every node's picture is in or
// it is late.

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "run/node_driver.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::harness {

class PictureDriver final : public NodeDriver {
 public:
  /// `ids`: the nodes, ascending (the center, 0, first). `stop_check` is called at least every
  /// 50 ms while waiting; it throws RunAborted to end the run (a signal, a failed node).
  PictureDriver(const transport::NodeConfig& config, std::uint64_t run_id, std::vector<int> ids,
                std::function<void()> stop_check);

  /// Until every node announced READY and the harness's endpoints match them.
  void wait_until_joined(std::chrono::milliseconds timeout) override;

  /// Lock-step round k: its tick, then every node's picture of step k (node order), within
  /// `timeout` (RunAborted otherwise).
  std::vector<wire::PictureRound> run_round(std::uint32_t k, std::chrono::milliseconds timeout);

  /// Real time: the start tick (step 0 begins at `epoch`), then each of the `steps` rounds
  /// handed to `on_round` in step order with the pictures that came (node order), once every
  /// node's is in or `late_after` has passed since the round's scheduled end.
  void run_realtime(int steps, double time_step_s, std::chrono::system_clock::time_point epoch,
                    std::chrono::milliseconds late_after,
                    const std::function<void(int, std::vector<wire::PictureRound>)>& on_round);

  /// The harness killed station `id` (true) or started it again (false).
  void set_down(int id, bool down) override;
  /// Until a restarted station has announced READY again.
  void wait_until_ready(int id, std::chrono::milliseconds timeout) override;

  /// What a node reported when it finished.
  struct Finished {
    std::uint32_t resyncs = 0;  ///< rounds it took another station's picture
    std::uint64_t lost = 0;     ///< samples the simulated loss removed
    DropCounts dropped{};       ///< samples it refused, by kind
  };
  /// Waits up to `timeout` for every node's FINISHED status; what each reported.
  std::map<int, Finished> wait_finished(std::chrono::milliseconds timeout);

  /// Releases the nodes: they exit once they hear it.
  void release();

 private:
  void check();

  std::uint64_t run_id_;
  std::vector<int> ids_;  // ascending
  std::function<void()> stop_check_;
  transport::DdsNode node_;
  transport::Writer<wire::Tick> ticks_;
  transport::Reader<wire::PictureRound> rounds_;
  transport::Reader<wire::StationStatus> statuses_;
  transport::ReaderWaitSet wait_set_;
  std::map<int, std::uint64_t> ready_;  // node -> the process instance that announced READY
  std::map<int, std::uint64_t> killed_instance_;
  std::set<int> down_;  // stations killed and not restarted: not waited for
  std::map<int, Finished> finished_;
};

}  // namespace skyfuse::harness
