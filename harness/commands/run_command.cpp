#include "commands/run_command.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <limits>

#include "report/picture_run_report.hpp"
#include "run/picture_run.hpp"
#include "run/placement.hpp"
#include "run/simulated_hosts.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/options/number_checks.hpp"
#include "skyfuse/options/scenario_option.hpp"
#include "skyfuse/sim/any_plan.hpp"
#include "skyfuse/transport/node_config.hpp"
#include "skyfuse/transport/node_plan.hpp"

namespace skyfuse::harness {
namespace {
// "ID@STEP" -> {ID, STEP}.
StationEvent parse_station_event(const std::string& option, const std::string& text) {
  const auto pair = options::parse_number_pair(text, '@');
  if (!pair || pair->first > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
    throw CLI::ValidationError(option, "expected ID@STEP, e.g. 2@100, got " + text);
  }
  return {static_cast<int>(pair->first), pair->second};
}

// "[ADDRESS:]PORT" -> {ADDRESS or loopback, PORT}; whether the address is this machine's is
// found when the server binds to it.
LiveEndpoint parse_live_endpoint(const std::string& text) {
  LiveEndpoint e;
  const auto colon = text.rfind(':');
  const std::string port = colon == std::string::npos ? text : text.substr(colon + 1);
  if (colon != std::string::npos) e.address = text.substr(0, colon);
  in6_addr any{};
  if (inet_pton(AF_INET, e.address.c_str(), &any) != 1 &&
      inet_pton(AF_INET6, e.address.c_str(), &any) != 1) {
    throw CLI::ValidationError("--live", "'" + e.address + "' is not an IP address");
  }
  unsigned number = 0;
  const auto [end, error] = std::from_chars(port.data(), port.data() + port.size(), number);
  if (e.address.empty() || port.empty() || error != std::errc{} ||
      end != port.data() + port.size() || number > 65535) {
    throw CLI::ValidationError("--live",
                               "expected [ADDRESS:]PORT with PORT in [0, 65535], e.g. "
                               "8765 or 127.0.0.1:8765, got '" +
                                   text + "'");
  }
  e.port = static_cast<std::uint16_t>(number);
  return e;
}

// Runs `execute` (a run of either kind) and prints its table (`print_table`), where its files
// are and, for a run stopped once its rounds began, how many steps it recorded — then rethrows
// the stop, which main reports.
template <typename Summary, typename Execute>
Summary report_run(const RunOptions& o, void (*print_table)(const Summary&, std::FILE*),
                   const Execute& execute) {
  const auto report = [&](const Summary& summary) {
    print_table(summary, stdout);
    fmt::print("results in {}{}\n", o.out_dir,
               summary.stop_cause ? fmt::format(" (the {} of {} steps recorded before the run "
                                                "stopped)",
                                                summary.steps, summary.steps_planned)
                                  : "");
    if (!o.record_path.empty()) fmt::print("recording in {}\n", o.record_path);
  };
  try {
    Summary summary = execute();
    report(summary);
    return summary;
  } catch (const StoppedEarlyWith<Summary>& e) {
    report(e.summary());  // every file is written; main says why the run stopped
    throw;
  }
}

}  // namespace

void add_run_command(CLI::App& app, RunOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "run", "Run the stations and the fusion center as processes over DDS, in lock-step");
  options::add_scenario_option(*cmd, o.node.scenario_path);
  options::add_traffic_file_option(*cmd, o.node.traffic_file);
  options::add_plan_options(*cmd, o.node.overrides);
  cmd->add_option("--out", o.out_dir, "Folder for the per-step CSVs and summary.json")
      ->capture_default_str();
  options::add_domain_option(*cmd, o.node.domain);
  cmd->add_option("--run-id", o.run_id, "Run id (default: random)");
  options::add_qos_option(*cmd, o.node.qos_file);
  options::add_secure_option(*cmd, o.node.secure_dir);
  cmd->add_option("--discovery-timeout", o.discovery_timeout_s,
                  "Seconds to wait until every process has joined (default: 30, or 2 per station "
                  "from 16 stations up)")
      ->check(options::positive_number());
  cmd->add_option("--round-timeout", o.round_timeout_s,
                  "Seconds a running node may deliver no track before the run is abandoned")
      ->check(options::positive_number())
      ->capture_default_str();
  options::add_deadline_options(*cmd, o.node);
  options::add_loss_options(*cmd, o.node.loss, o.node.best_effort);
  options::add_delay_options(*cmd, o.node.delay);
  options::add_refusion_option(*cmd, o.node.refusion_lag);
  options::add_nis_gate_option(*cmd, o.node.gate);
  options::add_network_options(*cmd, o.node.network);
  cmd->add_option_function<std::vector<std::string>>(
         "--kill",
         [&o](const std::vector<std::string>& all) {
           for (const std::string& text : all)
             o.kills.push_back(parse_station_event("--kill", text));
         },
         "Kill station ID with SIGKILL before the round of STEP, as ID@STEP (repeatable)")
      ->type_name("ID@STEP");
  cmd->add_option_function<std::vector<std::string>>(
         "--restart",
         [&o](const std::vector<std::string>& all) {
           for (const std::string& text : all) {
             o.restarts.push_back(parse_station_event("--restart", text));
           }
         },
         "Start killed station ID again as a new process before the round of STEP, as ID@STEP")
      ->type_name("ID@STEP");
  cmd->add_option("--replay", o.replay_path,
                  "Stations replay their measurements from this CSV (a measurements.csv of an "
                  "earlier run) instead of simulating them")
      ->check(CLI::ExistingFile);
  cmd->add_option("--record", o.record_path,
                  "Also write the run as an MCAP recording (Foxglove, Lichtblick, skyfuse view)")
      ->type_name("FILE.mcap");
  cmd->add_option("--asterix-record", o.asterix_record_path,
                  "A run of many aircraft: also write every node's picture each round as ASTERIX "
                  "CAT062 system tracks, UDP datagrams in a pcap file (Wireshark reads it)")
      ->type_name("FILE.pcap");
  options::add_asterix_out_option(*cmd, o.node.asterix_out);
  options::add_asterix_replay_option(*cmd, o.node.asterix_replay);
  options::add_asterix_in_options(*cmd, o.node);
  CLI::Option* live =
      cmd->add_option_function<std::string>(
             "--live", [&o](const std::string& text) { o.live = parse_live_endpoint(text); },
             "Stream the run while it goes on: a Foxglove WebSocket server, and skyfuse's page "
             "over "
             "HTTP, on [ADDRESS:]PORT (loopback unless ADDRESS is given; PORT 0: any free port)")
          ->type_name("[ADDRESS:]PORT");
  cmd->add_option("--live-scene-hz", o.live_scene_hz,
                  "--live: scenes, frames and map fixes a second at most, skyfuse's own channels "
                  "going out every round (0: everything every round)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str()
      ->needs(live);
  cmd->add_option("--hosts", o.hosts,
                  "Place the center and the stations, round robin, on N simulated hosts: network "
                  "namespaces joined by a bridge, discovering through the harness (root only)")
      ->check(options::whole_number_in(1, SimulatedHosts::kMaxHosts));
  cmd->add_option(
         "--stations-per-process", o.stations_per_process_given,
         "Run K stations in each station process, sharing its DDS participant (for "
         "simulation on one host or on --hosts: fewer participants to discover, and the "
         "samples between stations of one process pass in memory; the wire and the "
         "results are those of one process per station). Not with --secure, --external, "
         "--kill or --restart. Default: 1 up to 8 stations, ceil(sqrt(M)) above (1 where refused)")
      ->check(CLI::Range(1, 256));
  options::add_discovery_option(
      *cmd, o.discovery,
      "How the processes find each other: auto (on one host peers for a tree of 16 or more "
      "stations the harness starts, when their fixed ports are free and below the kernel's "
      "ephemeral range, multicast otherwise; the harness's discovery server across --hosts), "
      "multicast (every participant announces itself to all), server "
      "(--hosts only), or peers (each announces itself only to the processes it exchanges "
      "with, so a station discovers its cluster, not every station)");
  cmd->add_flag("--external", o.external,
                "Do not start processes: drive stations and a center started elsewhere");
  cmd->add_flag("-v,--verbose", o.verbose, "Let the node processes log at info level");
}

int run_run(const RunOptions& given) {
  // The run's kind is its plan's (sim/any_plan.hpp).
  const AnyPlan any_plan = transport::load_any_plan(given.node);
  // How many stations share a process is the run's to pick, for both kinds, unless told.
  RunOptions o = given;
  o.stations_per_process = given.stations_per_process_given.value_or(
      Placement::auto_stations_per_process(given, static_cast<std::size_t>(stations_of(any_plan))));
  if (const auto* plan = std::get_if<PicturePlan>(&any_plan)) {
    const PictureRunSummary summary =
        report_run(o, print_picture_run_table, [&] { return execute_picture_run(o, *plan); });
    // Without faults every picture is its in-process twin's; with loss, a kill or the wall
    // clock (a late scan) the peers must agree again by the end.
    const bool held = summary.faults || summary.realtime
                          ? summary.last_round_peers_apart + 1 < summary.steps
                          : summary.peers_identical && summary.equals_in_process &&
                                summary.center_equals_in_process;
    return held ? 0 : 1;
  }
  const RunPlan& plan = std::get<RunPlan>(any_plan);
  warn_if_receive_buffers_too_small(plan.stations);
  report_run(o, print_run_table, [&] { return execute_run(o, plan); });
  return 0;
}

}  // namespace skyfuse::harness
