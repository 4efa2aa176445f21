#pragma once
/// \file
/// How a station or the fusion center announces itself on the status topic, and how it finds
/// out that another live process already holds its id in the same run.
///
/// Every process draws a random instance number and notes its start time. Status samples are
/// durable, so a newcomer receives the latest status of every process already running; if one
/// has the same run and id, the newer of the two (later start, then larger instance) must go.

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/refusal_reports.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::transport {

class NodePresence {
 public:
  NodePresence(DdsNode& node, std::uint64_t run_id, int node_id);

  /// Publishes this node's state, with the drop counts last given to set_drops().
  void announce(wire::NodeState state, std::uint32_t step = 0, const std::string& detail = {});
  /// A READY status of round `step` with the drop counts last given to set_drops(), in
  /// kRefusalReportsPartition.
  void report_refusals(std::uint32_t step);
  void set_drops(const DropCounts& drops) { drops_ = drops; }
  /// Samples removed by the simulated loss, and rounds that resynchronised this node's prior.
  void set_link_counts(std::uint64_t lost, std::uint32_t resyncs, std::uint64_t late_used) {
    lost_ = lost;
    resyncs_ = resyncs;
    late_used_ = late_used;
  }
  /// Waits until every reader has the last announcement: call before exiting.
  bool wait_delivered(std::chrono::milliseconds timeout) {
    return writer_.wait_acknowledged(timeout);
  }

  /// Reads status samples received so far. Returns a description of an older process with
  /// this node's id in this run, if one was seen: this process is then the duplicate.
  std::optional<std::string> find_older_twin();

  std::uint64_t instance() const { return instance_; }

 private:
  const DdsNode& node_;  // for the participants it knows
  std::uint64_t run_id_;
  int node_id_;
  std::uint64_t instance_;
  std::uint64_t started_ns_;
  wire::StationStatus status(wire::NodeState state, std::uint32_t step,
                             const std::string& detail) const;

  Writer<wire::StationStatus> writer_;
  Writer<wire::StationStatus> refusal_reports_;
  Reader<wire::StationStatus> reader_;
  std::optional<std::string> older_twin_;
  DropCounts drops_{};
  std::uint64_t lost_ = 0;
  std::uint32_t resyncs_ = 0;
  std::uint64_t late_used_ = 0;
};

/// A node's last act after announcing FINISHED: waits until the harness releases it with a
/// stop tick of `run_id` (it sends one once it holds every node's last track and status), and
/// if none comes within `timeout`, until its last samples are acknowledged. Waiting for the
/// release rather than for acknowledgements matters after a crash: a killed peer's readers
/// stay matched until their lease expires, and would never acknowledge anything.
/// True if the harness released the node.
template <typename TrackWriter>
bool finish_when_released(Reader<wire::Tick>& ticks, std::uint64_t run_id, NodePresence& presence,
                          TrackWriter& tracks, std::chrono::milliseconds timeout) {
  const auto give_up = std::chrono::steady_clock::now() + timeout;
  wire::Tick tick;
  while (std::chrono::steady_clock::now() < give_up) {
    while (ticks.take(tick)) {
      if (tick.run_id() == run_id && tick.stop()) return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  tracks.wait_acknowledged(std::chrono::seconds(2));
  presence.wait_delivered(std::chrono::seconds(2));
  return false;
}

/// Ends a node the harness has released, with `code`, without deleting its DDS participant.
/// Deleting it sends every other participant a goodbye, and a process that handles one while
/// its lease timer for the same participant fires aborts in Debian's Fast DDS 2.9 (the
/// `PDP::check_remote_participant_liveliness` assertion): at M = 64 every node receives 65
/// goodbyes at once. Without them the others drop the node at their own exit or when its lease
/// expires. Nothing is lost: the transport is UDP only (no shared-memory segment to leave
/// behind), logs are flushed here, and the harness holds every sample the node owed it.
[[noreturn]] void leave_without_goodbye(int code);

/// A node process's round object (a station, the center, which own the DDS participant), made
/// to live until leave_without_goodbye ends the process. Destroying it would delete the
/// participant and send the goodbye above; a node made this way leaves without one however its
/// run ends: released, stopped by a tick, by a signal, on an error or an exception.
template <typename Process, typename... Args>
Process& make_lifelong(Args&&... args) {
  return *new Process(std::forward<Args>(args)...);  // never deleted: the process _Exits
}

}  // namespace skyfuse::transport

namespace skyfuse::transport {

enum class JoinOutcome { kJoined, kTimedOut, kDuplicate, kShutdown };

struct JoinResult {
  JoinOutcome outcome = JoinOutcome::kJoined;
  std::string detail;  ///< for kDuplicate: who holds the id; for kTimedOut: what is missing
};

/// Announces STARTING, waits until `all_matched()` holds, then listens a little longer for the
/// durable statuses of processes already running (matching precedes their delivery) and checks
/// that no older process holds this id. Announces READY when joined.
/// `describe_missing` says what is still unmatched, for the timeout message.
JoinResult join_run(NodePresence& presence, const std::function<bool()>& all_matched,
                    const std::function<std::string()>& describe_missing,
                    std::chrono::milliseconds timeout);

/// kExitDuplicateId, with the message, if an older process holding this id has announced itself
/// by now; nullopt otherwise. Nodes call it while they wait, not only while joining: on a busy
/// machine the older process's durable status can arrive after the join window.
std::optional<int> exit_code_if_duplicate(NodePresence& presence, const std::string& who,
                                          std::uint64_t run_id);

/// Logs why joining failed, in the words a user needs, and returns the process exit code;
/// nullopt when the node joined. `who` names the node: "station 3", "a fusion center".
std::optional<int> exit_code_unless_joined(const JoinResult& result, NodePresence& presence,
                                           const std::string& who, std::uint64_t run_id,
                                           double timeout_s);

}  // namespace skyfuse::transport
