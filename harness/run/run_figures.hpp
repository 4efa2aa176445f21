#pragma once
// What the house (run/run_over_dds.hpp) measures of a run over DDS, whichever its kind: how the
// run was laid out, how it ended, how its processes found each other, what they cost, and what
// the host could not carry. RunSummary (one aircraft, run/run_report.hpp) and PictureRunSummary
// (many, run/picture_run.hpp) are each one, with their own figures beside; so a figure the
// house measures is there for both kinds, under one name.

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "run/run_aborted.hpp"

namespace skyfuse::harness {

/// What the house measured of one start of the processes, for the kind's summary.
struct ProcessMeasures {
  /// How the processes discovered each other ("multicast", "server ADDRESS:PORT", "peers"),
  /// and how long it took from their start until every node joined.
  std::string discovery;
  double discovery_s = 0.0;
  /// The wait for discovery to go quiet before the first round (run/discovery_quiet.hpp).
  double settle_s = 0.0;
  bool settled_quiet = false;
  double rounds_s = 0.0;  ///< wall time of the rounds
  /// UDP datagrams the kernel delivered to the run's sockets per round (none if unreadable),
  /// and CPU of every process (stations, center, harness) per station and round, ms.
  std::optional<double> datagrams_per_round;
  double cpu_ms_per_station_round = 0.0;
  double node_peak_resident_mib = 0.0;  ///< the largest of any node at the end of the rounds
  std::map<std::string, std::string> node_exits;  ///< how each node process ended, by name
  /// Why the rounds stopped before the last, if they did.
  std::optional<RunAborted> stopped;
  /// The rounds' time base: when step 0 began, ns since the Unix epoch.
  std::uint64_t epoch_ns = 0;
  bool realtime = false;
};

struct RunFigures {
  int stations = 0;
  int steps = 0;          ///< rounds recorded
  int steps_planned = 0;  ///< the run's rounds; more than `steps` when it stopped early
  /// Why the run stopped before its last round, and the message that said so; none for a run
  /// that completed (summary.json's `ended`: "complete" or to_string(cause)).
  std::optional<StopCause> stop_cause;
  std::string end_detail;
  std::string exchange = "flat";  ///< "flat" or "tree", as the run's plan chose it
  int fanout = 0;                 ///< the tree's stations per cluster; 0 for flat
  int stations_per_process = 1;   ///< stations sharing a process (run/station_groups.hpp)
  /// How the processes discovered each other ("multicast", "server ADDRESS:PORT", "peers"),
  /// and seconds from their start until every node joined.
  std::string discovery = "multicast";
  double discovery_s = 0.0;
  /// Seconds from every node's READY to the first round, waiting for discovery to go quiet
  /// (run/discovery_quiet.hpp), and whether it did within the limit.
  double settle_s = 0.0;
  bool settled_quiet = true;
  double rounds_per_s = 0.0;
  /// Counted by the kernel over the rounds (run/kernel_counters.hpp): UDP datagrams received
  /// per round by every process of the run (none when a count could not be read), CPU time
  /// per station and round (stations, center and harness together), and the largest peak
  /// resident memory of one node.
  std::optional<double> datagrams_per_round;
  double cpu_ms_per_station_round = 0.0;
  double node_peak_resident_mib = 0.0;
  /// How each node process the harness started ended, by name ("station 3": "exit 0", "signal
  /// 9 (Killed)"); a station killed on purpose (--kill) is not listed.
  std::map<std::string, std::string> node_exits;
  /// What this host could not carry, in one line (empty when it carried the run): printed at
  /// the end and kept in summary.json.
  std::string host_verdict;

  /// What the house measured of the processes, and how the rounds ended.
  void take(const ProcessMeasures& measured);
};

/// How a real-time run went, for host_verdict: its deadline (0: lock-step, nothing to say), the
/// share of its rounds with every input in time, and, when it fell behind, the rounds complete
/// and how far behind the schedule it was when it stopped.
struct RealtimeLoad {
  double deadline_ms = 0.0;
  double share_in_time = 0.0;
  int rounds_complete = 0;
  double behind_s = 0.0;
};

/// One line on what this host could not carry: for a real-time run that fell behind, or that
/// kept fewer than 99 % of its rounds' inputs in time; empty otherwise. `cpu` and `cores` name
/// the host; the CPU per station-round says how many cores the rate would take.
std::string host_verdict(const RunFigures& s, const RealtimeLoad& load, double time_step_s,
                         const std::string& cpu, unsigned cores);

}  // namespace skyfuse::harness
