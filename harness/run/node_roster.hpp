#pragma once
// The harness's side of the nodes of a run over DDS, whichever its kind: the ticks it sends
// (each lock-step round's, the real-time start, the stop), the statuses the nodes publish
// (READY, FAILED, FINISHED with their counts), the refusals they report as the run goes on, and
// which stations the harness has killed. Both drivers keep one (run/lockstep_driver.hpp: one
// aircraft's tracks and measurements; run/picture_driver.hpp: many aircraft's pictures) and
// read their own samples beside it; the house (run/run_over_dds.hpp) joins the nodes, kills
// and restarts stations through it. So joining, a restart's READY, a failed node and the
// nodes' final counts are handled alike for both kinds.

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "run/round_record.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::harness {

/// How messages name node `id`: "center" (id 0) or "station <id>"; also the name its process
/// is started under, so that a message about either points at the same node.
std::string node_name(int id);

/// The harness's key among node ids in drop counts.
inline constexpr int kHarnessNodeId = -1;

/// What a node reported when it finished.
struct NodeCounts {
  DropCounts dropped{};
  std::uint64_t lost = 0;                ///< received samples removed by the simulated loss
  std::uint32_t resyncs = 0;             ///< rounds fused onto another station's prior
  std::uint64_t late_used = 0;           ///< samples kept after their round closed, and re-fused
  std::uint32_t participants_known = 0;  ///< other DDS participants it had discovered
};

class NodeRoster {
 public:
  using Clock = std::chrono::steady_clock;

  /// `ids`: every node of the run, the center (0) among them. `stop_check` is called at least
  /// every 50 ms while waiting; it throws RunAborted to end the run (a signal, a failed node).
  NodeRoster(const transport::NodeConfig& config, std::uint64_t run_id, std::vector<int> ids,
             std::function<void()> stop_check);

  /// The participant the driver makes its own readers on, and the wait set they join.
  transport::DdsNode& node() { return node_; }
  transport::ReaderWaitSet& wait_set() { return wait_set_; }
  /// An endpoint of the driver's that must match `expected` nodes before the run has joined,
  /// as `name` (e.g. "track writers") in the message of a discovery that timed out.
  void expect_matched(std::string name, std::function<int()> matched, int expected);
  /// Called while the roster waits (joining, a restart, the end), to keep the driver's reader
  /// queues short.
  void while_waiting(std::function<void()> drain) { drain_ = std::move(drain); }

  /// Until every node announced READY and every endpoint matched (RunAborted after `timeout`,
  /// naming what is missing).
  void wait_until_joined(std::chrono::milliseconds timeout);
  /// The harness killed station `id` (true) or started it again (false): a station down is not
  /// waited for.
  void set_down(int id, bool down);
  bool is_down(int id) const { return down_.contains(id); }
  /// The nodes not down.
  std::size_t nodes_up() const { return ids_.size() - down_.size(); }
  /// When node `id` last joined or came back up (silence is counted from then).
  Clock::time_point up_since(int id) const;
  /// Until a restarted station has announced READY again.
  void wait_until_ready(int id, std::chrono::milliseconds timeout);

  /// The stop check, then read_statuses().
  void check();
  /// Every status and refusal report that came: RunAborted (kNodeFailed) for a node that
  /// FAILED.
  void read_statuses();
  /// Blocks until a sample arrives on an attached reader or `slice` has passed.
  void wait(std::chrono::milliseconds slice) { wait_set_.wait(slice); }

  /// Lock-step round k's tick (sent again by the caller until the round is in: a station
  /// restarted just before it may match the tick writer a moment after the first copy).
  void send_tick(std::uint32_t k);
  /// Real time: the one start tick; step 0 begins at `epoch_ns` (ns since the Unix epoch).
  void send_start(std::uint64_t epoch_ns);
  /// Tells every node to stop; after the last round this releases the nodes waiting to exit.
  /// Best effort: the processes are ended by signal right after.
  void send_stop();

  /// Waits until every node that is up has announced FINISHED; false if `timeout` passed first.
  /// (No stop check: the rounds are over.)
  bool wait_until_finished(std::chrono::milliseconds timeout);
  /// What every node that announced FINISHED so far reported, by node id (0: the center).
  const std::map<int, NodeCounts>& finished() {
    read_statuses();
    return finished_;
  }
  /// The refusals reported since the last call, `harness_own` (the harness's own counts so
  /// far) with them under kHarnessNodeId, as of round `step`.
  std::vector<Refusal> take_refusals(std::uint64_t step, const DropCounts& harness_own);

 private:
  struct Expected {
    std::string name;
    std::function<int()> matched;
    int expected = 0;
  };
  // A node's counts so far, against those it reported before: what it refused in between.
  void note_refusals(int node_id, std::uint64_t instance, std::uint64_t step,
                     const DropCounts& counts);
  void wait_a_moment();

  std::uint64_t run_id_;
  std::vector<int> ids_;  // ascending
  std::function<void()> stop_check_;
  std::function<void()> drain_;
  transport::DdsNode node_;
  transport::Writer<wire::Tick> ticks_;
  transport::Reader<wire::StationStatus> statuses_;
  transport::Reader<wire::StationStatus> refusal_reports_;  // kRefusalReportsPartition
  transport::ReaderWaitSet wait_set_;
  std::vector<Expected> expected_;
  std::map<int, std::uint64_t> ready_;  // node -> the process instance that announced READY
  std::map<int, std::uint64_t> killed_instance_;
  std::set<int> down_;  // stations killed and not restarted
  std::map<int, Clock::time_point> up_since_;
  std::map<int, NodeCounts> finished_;
  // node -> (the process that reported, its counts then): for the refusals in between.
  std::map<int, std::pair<std::uint64_t, DropCounts>> reported_;
  std::vector<Refusal> refusals_;  // reported since the last take_refusals
};

}  // namespace skyfuse::harness
