#pragma once
// What one DDS run of the system is asked to do: the nodes' options (one contract with them)
// and what only the harness decides.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "run/run_report.hpp"
#include "skyfuse/options/node_options.hpp"

namespace skyfuse::harness {

/// `--live [ADDRESS:]PORT`: where the live stream and the page are served.
struct LiveEndpoint {
  std::string address = "127.0.0.1";  ///< loopback unless another address is given
  std::uint16_t port = 8765;          ///< 0: any free port, printed when the run starts
};

struct RunOptions {
  /// What every node of the run is given (scenario, plan, domain, QoS, security, deadlines,
  /// loss, NIS gate): one contract with the nodes, passed on by options::to_arguments. The
  /// harness fills in per run what only it knows: the run id, the timeouts, the log level.
  /// round_deadline_ms also sets when the harness records a round (twice it plus 250 ms).
  options::NodeOptions node;
  std::string out_dir = "results/run";
  std::optional<std::uint64_t> run_id;        ///< default: random
  std::optional<double> discovery_timeout_s;  ///< default: discovery_timeout_s() below
  double round_timeout_s = 10.0;              ///< a running node silent this long ends the run
  std::vector<StationEvent> kills;            ///< SIGKILL a station before a step's round
  std::vector<StationEvent> restarts;  ///< start a killed station again before a step's round
  std::string replay_path;  ///< stations replay measurements from this CSV instead of simulating
  /// Also write the run as an MCAP recording here (report/run_recording.hpp); empty: none.
  std::string record_path;
  /// A run of many aircraft: every node's picture each round as ASTERIX CAT062 in this pcap
  /// (report/picture_asterix.hpp); empty: none.
  std::string asterix_record_path;
  std::optional<LiveEndpoint> live;
  double live_scene_hz = 30.0;  ///< live scenes a second at most; 0: one every round  ///< stream
                                ///< the run while it goes on (report/live_feed.hpp)
  bool external = false;        ///< stations and center are started elsewhere (by hand, compose)
  int hosts = 0;  ///< > 0: place the processes on this many simulated hosts (simulated_hosts.hpp)
  /// Stations run by one process, sharing its participant (run/station_groups.hpp).
  int stations_per_process = 1;
  /// `--stations-per-process` as given; none: the run picks (auto_stations_per_process).
  std::optional<int> stations_per_process_given;
  /// How the processes discover each other (run/placement.hpp).
  options::Discovery discovery = options::Discovery::kAutomatic;
  bool verbose = false;
};

}  // namespace skyfuse::harness
