#pragma once
/// \file
/// Options every node process (station, fusion center) takes, so that a process started by
/// hand on any host joins the same run as the ones the harness starts.

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "skyfuse/options/network_options.hpp"
#include "skyfuse/random/link_delay.hpp"
#include "skyfuse/random/link_loss.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/validation/nis_gate.hpp"

namespace CLI {
class App;
}

namespace skyfuse::options {

/// Domain ids above 232 make Fast DDS 2.9 exit the process during participant creation.
inline constexpr int kMaxDomainId = 232;

struct NodeOptions {
  std::string scenario_path;  ///< empty: the embedded paper000 scenario
  /// A recorded traffic file (OpenSky state vectors) for a scenario with 'traffic: recorded',
  /// instead of the one it names; empty: its own.
  std::string traffic_file;
  int domain = 0;
  std::uint64_t run_id = 1;
  RunOverrides overrides;
  std::optional<std::string> qos_file;
  std::optional<std::string> secure_dir;  ///< DDS-Security identities from `skyfuse certs`
  double discovery_timeout_s = 30.0;
  double idle_timeout_s = 60.0;
  /// Real-time mode when > 0: each step starts on the wall clock at epoch + k dt and closes
  /// this many milliseconds later with whatever has arrived.
  double realtime_deadline_ms = 0.0;
  /// Lock-step: a round closes this many milliseconds after its tick with what has arrived
  /// (a dead station, or a lost sample, costs one deadline; nothing waits forever).
  double round_deadline_ms = 1000.0;
  /// Simulated loss of received increments and measurements (`--loss`, `--loss-steps`).
  LinkLoss loss;
  /// Simulated delay of received increments and measurements (`--link-delay-ms`,
  /// `--link-jitter-ms`), drawn with the loss's seed.
  LinkDelay delay;
  /// Fixed-lag re-fusion: how many closed rounds still take late samples and are fused again
  /// (`--refusion-lag`; 0: a late sample is refused as stale).
  std::size_t refusion_lag = 0;
  bool best_effort = false;  ///< increments and measurements BEST_EFFORT instead of RELIABLE
  /// The chi^2 gate on measurements (`--nis-gate P`; default: none).
  NisGate gate;
  /// The interface and the discovery (`--interface`, `--discovery-server`).
  NetworkOptions network;
  std::string log_level = "info";
  /// `--asterix-out HOST:PORT`: a node of a run of many aircraft sends its picture each round
  /// as ASTERIX CAT062 over UDP there (transport/picture_cat062.hpp); empty: it sends nothing.
  std::string asterix_out;
  /// `--asterix-replay FILE`: a station of a run of many aircraft whose sensor ASTERIX carries
  /// takes its scans from the CAT048/CAT021 records of its own SIC in the file (a pcap or raw
  /// ASTERIX blocks)
  /// (transport/asterix_replay.hpp) instead of simulating them; empty: it simulates.
  std::string asterix_replay;
  /// `--asterix-in HOST:PORT`: such a station takes its scans from a live UDP feed instead, a
  /// multicast group it joins or a port on this host (transport/asterix_live.hpp); empty: none.
  std::string asterix_in;
  /// `--asterix-in-wait-ms`: how long a station fed live waits for the feed to pass its round
  /// before it takes what came of it.
  double asterix_in_wait_ms = 1000.0;

  std::chrono::microseconds round_deadline() const;
  /// Real time: how long after its scheduled start a step closes (zero in lock-step).
  std::chrono::microseconds realtime_deadline() const;
  const NisGate& nis_gate() const { return gate; }
  std::chrono::milliseconds discovery_timeout() const;
  std::chrono::milliseconds idle_timeout() const;
  /// The wait for the first tick after joining. The harness ticks once every node has joined,
  /// and the others may still be discovering: this wait is discovery's, not the idle one (at
  /// M = 64 on 2 cores, discovery took 12-44 s and stations that joined first gave up after
  /// their 30 s idle timeout).
  std::chrono::milliseconds first_tick_timeout() const;
};

void add_node_options(CLI::App& app, NodeOptions& options);

/// The options of add_node_options that `skyfuse run` (and the other commands that start or
/// drive nodes) pass on unchanged: declared once, here.
void add_domain_option(CLI::App& app, int& domain);
/// `--traffic-file FILE.csv`: a recorded traffic file for a scenario with 'traffic: recorded'.
void add_traffic_file_option(CLI::App& app, std::string& traffic_file);
void add_qos_option(CLI::App& app, std::optional<std::string>& qos_file);
void add_secure_option(CLI::App& app, std::optional<std::string>& secure_dir);
/// `--realtime-deadline-ms D` and `--round-deadline-ms D`.
void add_deadline_options(CLI::App& app, NodeOptions& options);
/// `--asterix-out HOST:PORT`, checked as an IPv4 address and a port.
void add_asterix_out_option(CLI::App& app, std::string& destination);
/// `--asterix-replay FILE`, an existing file.
void add_asterix_replay_option(CLI::App& app, std::string& file);
/// `--asterix-in HOST:PORT` (checked as --asterix-out is, and not with --asterix-replay) and
/// `--asterix-in-wait-ms`.
void add_asterix_in_options(CLI::App& app, NodeOptions& options);

/// The command line that gives a node exactly `options`: add_node_options parses it back to
/// the same values, bit for bit (a unit test shows it). The one place where options become a
/// child process's arguments.
std::vector<std::string> to_arguments(const NodeOptions& options);

/// `--stations M`, `--steps K`, `--speed-kmh V` and `--mc-run N` into `overrides`: what makes a
/// RunPlan of the scenario, shared by the nodes and `skyfuse run`, which passes them on.
void add_plan_options(CLI::App& app, RunOverrides& overrides);
/// `--associator NAME`: a run of many aircraft with another data associator.
void add_associator_option(CLI::App& app, std::optional<std::string>& associator);

/// `--exchange flat|tree` and `--fanout K`: the scenario's network block, overridden.
void add_exchange_options(CLI::App& app, std::optional<ExchangeConfig::Kind>& exchange,
                          std::optional<int>& fanout);

/// `--loss P`, `--loss-steps A:B`, `--loss-seed S` and `--best-effort` into `loss` and
/// `best_effort`: shared by the nodes and `skyfuse run`, which passes them on.
void add_loss_options(CLI::App& app, LinkLoss& loss, bool& best_effort);
/// `--link-delay-ms D` and `--link-jitter-ms J` into `delay`: shared by the nodes and `skyfuse
/// run`, which passes them on.
void add_delay_options(CLI::App& app, LinkDelay& delay);
/// `--refusion-lag L` into `lag`.
void add_refusion_option(CLI::App& app, std::size_t& lag);
/// The largest --refusion-lag: the rounds a node keeps, each with its prior and contributions.
inline constexpr std::size_t kMaxRefusionLag = 64;
/// The arguments that give a node the same delay (empty when there is none).
std::vector<std::string> delay_arguments(const LinkDelay& delay);
/// "A<separator>B" with A and B unsigned decimal integers and nothing else (no sign, no
/// spaces); nothing if the text is not that. For option values like `100:200` and `2@100`.
std::optional<std::pair<std::uint64_t, std::uint64_t>> parse_number_pair(std::string_view text,
                                                                         char separator);

/// `--nis-gate P` into `gate`.
void add_nis_gate_option(CLI::App& app, NisGate& gate);
/// The arguments that give a node the same loss settings (empty when there is no loss).
std::vector<std::string> loss_arguments(const LinkLoss& loss, bool best_effort);

/// Exit codes shared by the node processes, so the harness can say what happened.
enum ExitCode : int {
  kExitOk = 0,
  kExitError = 1,
  kExitUsage = 2,
  kExitDuplicateId = 3,
  kExitDiscoveryTimeout = 4,
  kExitIdleTimeout = 5,
  kExitNumerical = 6,
};

}  // namespace skyfuse::options

namespace skyfuse::options {

/// Runs a node's body and turns what escapes it into one logged line and an exit code: bad
/// options or scenario -> kExitUsage, anything else -> kExitError.
int run_node(const std::function<int()>& body);

}  // namespace skyfuse::options
