#pragma once
// One start of every process of a run over DDS, whichever its kind: the house that one aircraft
// (execute_run.cpp) and many (picture_run.cpp) share. The house refuses what cannot start,
// starts the center and the station processes, waits until they have joined and discovery has
// gone quiet, drives the rounds on its clock (lock-step: station kills and restarts before their
// round, the first rounds checked for a connected network; real time: one start tick), measures
// the processes (CPU, datagrams, peak memory), and ends them, keeping what was recorded when the
// rounds stop early. A kind (RunKind) says what differs: what its nodes are told, its driver's
// rounds and their check, its summary and files. So every behaviour of the house exists for both
// kinds, because there is one.

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "run/connection_check.hpp"
#include "run/node_roster.hpp"
#include "run/run_aborted.hpp"
#include "run/run_figures.hpp"
#include "run/run_options.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/transport/node_config.hpp"

namespace skyfuse::harness {

/// What differs between a run of one aircraft and a run of many, as the house sees it.
class RunKind {
 public:
  virtual ~RunKind() = default;

  /// The stations taking part (ascending), how many the run counts (discovery waits and leases
  /// are sized by it), its rounds, and the word its progress line starts with.
  virtual std::vector<int> station_ids() const = 0;
  virtual int stations() const = 0;
  virtual int steps() const = 0;
  virtual std::string progress_label() const = 0;
  /// The exchange the processes are placed and discover each other for.
  virtual ExchangeConfig placement_exchange() const = 0;
  /// What every node is told beyond `child` (the run's node options): the plan's overrides.
  virtual void complete_node_options(options::NodeOptions& child) const = 0;
  /// Arguments only a station process takes.
  virtual std::vector<std::string> station_arguments() const { return {}; }

  /// Before any process starts: the kind's driver on `config`, and its live stream listening so
  /// that a client can be there for the first round. `check` is to be called at least every
  /// 50 ms while waiting; it throws RunAborted to end the run (a failed node, a signal).
  virtual void open(const transport::NodeConfig& config, std::uint64_t run_id,
                    std::function<void()> check) = 0;
  /// The nodes of the driver open() made: their joining, and kills and restarts between
  /// rounds.
  virtual NodeRoster& roster() = 0;

  /// The rounds begin; step 0 at `epoch_ns` (their recording's and live stream's time base).
  virtual void begin_rounds(std::uint64_t epoch_ns) = 0;
  /// Lock-step round k, recorded once `connection` has been told what it lacks.
  virtual void run_lockstep_round(int k, std::chrono::milliseconds round_timeout,
                                  ConnectionCheck& connection) = 0;
  /// Real time: the start tick (step 0 begins at `epoch`) and every round, `round_done` called
  /// after each is recorded. One aircraft's rounds stop (RunAborted) once they fall
  /// `round_timeout` behind the schedule; a picture hands a late round over with the pictures
  /// that came (run/picture_driver.hpp), so its rounds never fall behind.
  virtual void run_realtime(std::chrono::system_clock::time_point epoch,
                            std::chrono::milliseconds round_timeout,
                            const std::function<void()>& round_done) = 0;
  /// The rounds the nodes worked on (at least those recorded): what is measured per round.
  virtual double rounds_worked() const = 0;
  /// Writes the summary and the files with the house's measures; when the rounds stopped
  /// early, throws StoppedEarlyWith<its summary> after writing them.
  virtual void end(const ProcessMeasures& measured, std::uint64_t run_id) = 0;
};

/// One start of every process of the run `kind` describes, as `o` says. Throws
/// std::invalid_argument for what cannot start, RunAborted when the run fails.
void run_over_dds(const RunOptions& o, RunKind& kind);

/// Seconds to wait until every process has joined: the option if given, else
/// default_discovery_timeout_s(stations).
double discovery_timeout_s(const RunOptions& options, int stations);

/// Kills and restarts must name participants (`participant_ids`), fit in a run of `steps`,
/// and alternate per station: kill, restart later, kill again later, ... Throws
/// std::invalid_argument naming the option otherwise.
void check_station_events(const RunOptions& o, const std::vector<int>& participant_ids, int steps);

/// The exit status of `skyfuse run` (and the commands that run the system) for a run that
/// ended with `e`: 128 + the signal when interrupted (130 for Ctrl-C), kExitStoppedEarly when
/// it fell behind real time or a node went silent, 1 otherwise (a node failed, discovery did
/// not complete, ...).
int exit_status_of(const RunAborted& e);
inline constexpr int kExitStoppedEarly = 3;

}  // namespace skyfuse::harness
