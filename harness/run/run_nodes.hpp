#pragma once
// The processes of one DDS run, whichever its kind (one aircraft: execute_run.cpp; many:
// picture_run.cpp): the center (process 0) and the station processes, --stations-per-process
// stations to a process, each started on its host with the arguments the run gives every node;
// a station killed and started again between rounds; a failed node or a signal ending the run
// (check); the kernel's counts over them (CPU, datagrams, peak memory); the wait for discovery
// to go quiet before the first round; and their end. What one kind of run does with its nodes,
// the other does too, because both do it here.

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "run/child_processes.hpp"
#include "run/discovery_quiet.hpp"
#include "run/kernel_counters.hpp"
#include "run/lockstep_driver.hpp"
#include "run/placement.hpp"
#include "run/run_options.hpp"
#include "run/station_groups.hpp"
#include "skyfuse/options/node_options.hpp"

namespace skyfuse::harness {

/// The scenario a run's options name: the file's text, or the embedded default's.
std::string run_scenario_text(const RunOptions& o);

/// Writes the scenario the nodes read (the file named by the options, or the embedded default)
/// into the results folder, which it makes, and returns its absolute path: what ran is what is
/// on disk.
std::filesystem::path write_run_scenario(const RunOptions& o);

/// What every node of a run is told, whichever its kind: the run's node options on `network`,
/// with the scenario's copy, the run id, the discovery wait, the idle limit and the log level the
/// harness decides. The caller adds what its kind decides (plan overrides, a traffic file).
options::NodeOptions node_options_for(const RunOptions& o, const options::NetworkOptions& network,
                                      const std::filesystem::path& scenario_file,
                                      std::uint64_t run_id, double discovery_timeout_s);

/// What a run refuses before anything starts, so that a refused command leaves an earlier run's
/// folder as it was: kills and restarts that do not fit the stations `ids` and `steps`
/// (check_station_events), a placement that cannot be (Placement::check), a security folder
/// without every node's identity.
void check_before_start(const RunOptions& o, const std::vector<int>& ids, int steps);

/// Real time: step 0 begins this long after every node joined, so that the start tick reaches
/// every node and discovery's last exchanges are over. At M = 64 both cores stay busy until
/// 0.2-0.3 s after the last node joins; with 300 ms, the first rounds ran beside them and came
/// late.
inline constexpr std::chrono::milliseconds kRealtimeHeadStart{1000};

/// The longest the rounds wait for discovery to go quiet after every node joined, and how long
/// before the nodes would give up waiting for the first tick that wait ends at the latest.
inline constexpr std::chrono::seconds kSettleLimit{60};
inline constexpr double kFirstTickMarginS = 10.0;

/// How long a node of the run may see no progress before it gives up (--idle-timeout).
double node_idle_timeout_s(const RunOptions& o);

class RunNodes {
 public:
  /// A node's arguments after the executable (and a station process's ids) on `network`.
  using NodeArguments =
      std::function<std::vector<std::string>(const options::NetworkOptions& network)>;

  /// The nodes of a run of the stations `ids` (ascending) placed by `placement`;
  /// `station_extra`: what every station process is given besides (--replay FILE).
  RunNodes(const RunOptions& o, const Placement& placement, std::vector<int> ids,
           NodeArguments arguments, std::vector<std::string> station_extra = {});

  /// Starts the center and every station process, unless the run drives nodes started
  /// elsewhere (--external).
  void start();
  /// Station `id` killed now with SIGKILL (a crash the run asked for), or started again as a new
  /// process that rejoins at `step`.
  void kill_station(int id);
  void restart_station(int id, std::uint64_t step);

  /// Throws RunAborted when a signal asked the harness to stop or a node failed.
  void check();

  /// The kernel's counts now over every process of the run and the harness, the CPU time of
  /// nodes that have left included.
  KernelSnapshot kernel_snapshot();
  /// Until the run's processes have gone quiet after discovery (discovery_quiet.hpp), at most
  /// kSettleLimit and kFirstTickMarginS before the nodes' wait for the first tick ends,
  /// check()ing between windows.
  QuietWait wait_until_quiet();
  /// The largest resident memory any live node has had, MiB.
  double peak_resident_mib() const;

  /// After the rounds (or a stop): waits up to `wait` for every node to exit by itself, ends
  /// the rest, and warns of any that failed after the rounds were recorded.
  void finish(std::chrono::milliseconds wait, bool stopped);
  /// Ends every node at once (the run failed).
  void terminate();

  /// How each node ended, by its name ("exit 0", "signal 9 (Killed)").
  std::map<std::string, std::string> exits() const;
  /// Processes in all: the center and the station processes.
  std::size_t processes() const { return groups_.processes(); }

 private:
  void spawn(std::size_t process, std::vector<std::string> argv, const std::string& name);
  /// The live nodes and the harness itself.
  std::vector<pid_t> run_processes() const;
  void spawn_stations(std::size_t process, std::optional<std::uint64_t> rejoin_step);

  const RunOptions& options_;
  const Placement& placement_;
  std::vector<int> ids_;
  NodeArguments arguments_;
  std::vector<std::string> station_extra_;
  StationGroups groups_;
  ChildProcesses children_;
  // One process per network namespace (a simulated host; -1: the harness's own), for the
  // kernel's UDP counters.
  std::map<int, pid_t> namespace_members_;
};

}  // namespace skyfuse::harness
