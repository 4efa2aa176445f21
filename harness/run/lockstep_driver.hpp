#pragma once
// The harness's side of a lock-step run over DDS: waits until every station and the center
// have joined, then for each step publishes Tick{run, k} and waits for every live process's
// track of step k (and every live station's measurement, which the harness records). Rounds
// close at a deadline like the nodes' own, so a node that is down or late is recorded as
// missing instead of stalling the run. The harness adds no estimation; it only observes.

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "run/node_roster.hpp"
#include "run/round_record.hpp"
#include "run/run_aborted.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/transport/node_config.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::harness {

/// The name a station process is started under: its station's node_name, or "stations A-B" for
/// several (ascending ids).
std::string process_name(std::span<const int> station_ids);

/// A random run id: samples of another run on the same domain carry another id and are dropped.
std::uint64_t fresh_run_id();

/// How long `nodes` processes on one host may take to discover each other: 30 s, and 2 s per
/// node from 16 nodes up - at 64 stations on 2 cores discovery took 12-44 s.
double default_discovery_timeout_s(int nodes);

/// What every track of a run carries: an estimate of the run's state dimension, and as many
/// mode probabilities as its filter has modes (0 for one model).
struct TrackShape {
  int state_dim = 0;
  std::size_t modes = 0;
};

class LockstepDriver final {
 public:
  /// `check` is called at least every 50 ms while waiting; it throws RunAborted to end the run.
  /// A track of another `shape` is refused.
  LockstepDriver(const transport::NodeConfig& config, std::uint64_t run_id,
                 std::span<const StationConfig> participants, TrackShape shape,
                 std::function<void()> check);
  ~LockstepDriver();

  /// The nodes' statuses, the ticks, joining, kills and restarts.
  NodeRoster& roster();

  /// Runs step k: publishes its tick and returns what the processes published for it, once
  /// every live one has or `close_after` has passed. A live node silent for `silence_limit`
  /// (over consecutive rounds) ends the run.
  RoundRecord run_round(std::uint64_t k, std::chrono::milliseconds close_after,
                        std::chrono::milliseconds silence_limit);

  /// Real-time mode: publishes the start tick (step 0 begins at `epoch`) and gathers every
  /// node's track of every step as the nodes publish them on their own clocks; `on_round` is
  /// given each step, in step order, as soon as it is complete. The run is abandoned
  /// (RunAborted, StopCause::kFellBehind) once the steps complete lag the schedule by more than
  /// `timeout` (the schedule's end included), after handing over every step any track reached;
  /// realtime_progress() then says how far it got.
  void run_realtime(int steps, double time_step_s, std::chrono::system_clock::time_point epoch,
                    std::chrono::milliseconds timeout,
                    const std::function<void(RoundRecord)>& on_round);

  /// How far a real-time run had got: the steps the schedule had reached, the furthest step
  /// any node's track arrived for, and how long ago the first step not yet complete was due.
  struct RealtimeProgress {
    std::uint64_t steps_scheduled = 0;
    std::uint64_t steps_reached = 0;
    double behind_s = 0.0;
  };
  RealtimeProgress realtime_progress() const;

  /// What every node that has announced FINISHED so far reported, by node id (0: center),
  /// and the harness's own drops under kHarnessNodeId.
  /// Refusals reported since the last round's record (the nodes' last statuses after the
  /// run), the harness's own with them, as of round `step`.
  std::vector<Refusal> take_refusals(std::uint64_t step);
  std::map<int, NodeCounts> finished_counts();

  /// The settled tracks received (fixed-lag re-fusion: each round's final estimate), by
  /// (step, source id).
  const std::map<std::pair<std::uint64_t, int>, ReceivedTrack>& settled_tracks() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace skyfuse::harness
