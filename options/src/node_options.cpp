#include "skyfuse/options/node_options.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "skyfuse/asterix/udp.hpp"
#include "skyfuse/options/number_checks.hpp"
#include "skyfuse/options/scenario_option.hpp"
#include "skyfuse/picture/associator.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"

namespace skyfuse::options {

std::chrono::microseconds NodeOptions::realtime_deadline() const {
  return std::chrono::microseconds(std::llround(realtime_deadline_ms * 1000.0));
}
std::chrono::microseconds NodeOptions::round_deadline() const {
  return std::chrono::microseconds(std::llround(round_deadline_ms * 1000.0));
}

std::chrono::milliseconds NodeOptions::discovery_timeout() const {
  return std::chrono::milliseconds(static_cast<long>(discovery_timeout_s * 1000.0));
}
std::chrono::milliseconds NodeOptions::idle_timeout() const {
  return std::chrono::milliseconds(static_cast<long>(idle_timeout_s * 1000.0));
}
std::chrono::milliseconds NodeOptions::first_tick_timeout() const {
  return std::max(discovery_timeout(), idle_timeout());
}

void add_plan_options(CLI::App& app, RunOverrides& overrides) {
  app.add_option("--stations", overrides.stations,
                 "Number of participating stations: the first M of the scenario (default: all)")
      ->check(whole_number_at_least(1));
  app.add_option("--steps", overrides.steps, "Override the scenario's number of steps")
      ->check(whole_number_at_least(1));
  app.add_option("--speed-kmh", overrides.speed_kmh,
                 "Target speed (default: the first the scenario lists)")
      ->check(positive_number());
  app.add_option("--mc-run", overrides.mc_run,
                 "Monte-Carlo run index; selects the noise realisation")
      ->capture_default_str();
  add_exchange_options(app, overrides.exchange, overrides.fanout);
  app.add_option("--aircraft", overrides.aircraft,
                 "A scenario with generated traffic: how many aircraft (default: the scenario's)")
      ->check(whole_number_at_least(1));
  add_associator_option(app, overrides.associator);
}

void add_associator_option(CLI::App& app, std::optional<std::string>& associator) {
  // The registry's names, so that a new associator needs no line here.
  std::vector<std::string> names;
  for (const Associator& a : associators()) names.emplace_back(a.name);
  app.add_option("--associator", associator,
                 "A scenario with many aircraft: the tracker's data associator, one of " +
                     associator_names() +
                     " (default: the scenario's tracker.associator, gnn if it gives none)")
      ->check(CLI::IsMember(names));
}

void add_exchange_options(CLI::App& app, std::optional<ExchangeConfig::Kind>& exchange,
                          std::optional<int>& fanout) {
  app.add_option_function<std::string>(
         "--exchange",
         [&exchange](const std::string& name) { exchange = parse_exchange_kind(name); },
         "How peers exchange increments: flat (every station hears every station), tree "
         "(clusters of --fanout summed by an aggregator each) or auto (tree from 16 stations "
         "when there is no --loss, link delay or --refusion-lag, else flat; default: the "
         "scenario's, auto if it gives none)")
      ->check(CLI::IsMember({"flat", "tree", "auto"}));
  app.add_option("--fanout", fanout,
                 "Tree exchange: stations per cluster (default: the scenario's, 8 if it gives "
                 "none)")
      ->check(whole_number_in(2, ExchangeConfig::kMaxFanout));
}

void add_domain_option(CLI::App& app, int& domain) {
  app.add_option("--domain", domain, "DDS domain id")
      ->check(whole_number_in(0, kMaxDomainId))
      ->capture_default_str();
}

void add_qos_option(CLI::App& app, std::optional<std::string>& qos_file) {
  app.add_option("--qos", qos_file, "Fast DDS XML profiles overriding the built-in QoS")
      ->check(CLI::ExistingFile);
}

void add_secure_option(CLI::App& app, std::optional<std::string>& secure_dir) {
  app.add_option("--secure", secure_dir,
                 "DDS-Security: authenticate, authorise and encrypt with the identities in DIR "
                 "(made by `skyfuse certs DIR`)")
      ->check(CLI::ExistingDirectory);
}

void add_deadline_options(CLI::App& app, NodeOptions& o) {
  app.add_option("--realtime-deadline-ms", o.realtime_deadline_ms,
                 "Real-time mode: nodes step on the wall clock at the scenario's dt and each "
                 "round closes this many ms after it starts, with what has arrived (0: lock-step "
                 "on ticks)")
      ->check(non_negative_number());
  app.add_option("--round-deadline-ms", o.round_deadline_ms,
                 "Lock-step: a round closes this many ms after its tick with what has arrived")
      ->check(positive_number())
      ->capture_default_str();
}

void add_asterix_out_option(CLI::App& app, std::string& destination) {
  app.add_option("--asterix-out", destination,
                 "Send each round's picture as ASTERIX CAT062 system tracks over UDP to HOST:PORT "
                 "(IPv4, unicast or multicast; a run of many aircraft; docs/asterix.md)")
      ->check(udp_endpoint())
      ->type_name("HOST:PORT");
}

void add_asterix_replay_option(CLI::App& app, std::string& file) {
  app.add_option("--asterix-replay", file,
                 "Stations whose sensor ASTERIX carries (Mode S and 2-D radars, ADS-B / Remote ID) "
                 "take their scans from the CAT048/CAT021 records of their own SIC in this file "
                 "(a pcap, say an --asterix-record of the same scenario, or raw ASTERIX blocks) "
                 "instead of simulating them")
      ->check(CLI::ExistingFile)
      ->type_name("FILE");
}

void add_asterix_in_options(CLI::App& app, NodeOptions& o) {
  auto* in = app.add_option("--asterix-in", o.asterix_in,
                            "Stations whose sensor ASTERIX carries take their scans from a live "
                            "UDP feed of CAT048/CAT021 (their own SIC) on HOST:PORT: a multicast "
                            "group they join, or a port of this host (one station only)")
                 ->check(udp_endpoint())
                 ->type_name("HOST:PORT");
  if (auto* replay = app.get_option_no_throw("--asterix-replay")) in->excludes(replay);
  app.add_option("--asterix-in-wait-ms", o.asterix_in_wait_ms,
                 "How long a station fed by --asterix-in waits for the feed to pass its round "
                 "before it takes what came (in real time, keep it below the round deadline)")
      ->check(positive_number())
      ->capture_default_str();
}

void add_traffic_file_option(CLI::App& app, std::string& traffic_file) {
  app.add_option("--traffic-file", traffic_file,
                 "An OpenSky state-vector CSV for a scenario with 'traffic: recorded', instead of "
                 "the file it names")
      ->check(CLI::ExistingFile)
      ->type_name("FILE.csv");
}

void add_node_options(CLI::App& app, NodeOptions& o) {
  add_scenario_option(app, o.scenario_path);
  add_traffic_file_option(app, o.traffic_file);
  add_domain_option(app, o.domain);
  app.add_option("--run-id", o.run_id, "Run id shared by every process of the run")
      ->capture_default_str();
  add_plan_options(app, o.overrides);
  add_qos_option(app, o.qos_file);
  add_secure_option(app, o.secure_dir);
  app.add_option("--discovery-timeout", o.discovery_timeout_s,
                 "Seconds to wait for every peer to be discovered")
      ->check(positive_number())
      ->capture_default_str();
  app.add_option("--idle-timeout", o.idle_timeout_s,
                 "Seconds without progress after which the process gives up")
      ->check(positive_number())
      ->capture_default_str();
  add_deadline_options(app, o);
  add_loss_options(app, o.loss, o.best_effort);
  add_delay_options(app, o.delay);
  add_refusion_option(app, o.refusion_lag);
  add_nis_gate_option(app, o.gate);
  add_network_options(app, o.network);
  add_asterix_out_option(app, o.asterix_out);
  add_asterix_replay_option(app, o.asterix_replay);
  add_asterix_in_options(app, o);
  app.add_option("--log-level", o.log_level, "trace, debug, info, warn, error")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}))
      ->capture_default_str();
}

std::vector<std::string> to_arguments(const NodeOptions& o) {
  // "{}" writes a double's shortest representation that reads back to the same bits.
  std::vector<std::string> args;
  const auto add = [&](const char* flag, std::string value) {
    args.emplace_back(flag);
    args.push_back(std::move(value));
  };
  if (!o.scenario_path.empty()) add("--scenario", o.scenario_path);
  if (!o.traffic_file.empty()) add("--traffic-file", o.traffic_file);
  add("--domain", std::to_string(o.domain));
  add("--run-id", std::to_string(o.run_id));
  if (o.overrides.stations) add("--stations", std::to_string(*o.overrides.stations));
  if (o.overrides.steps) add("--steps", std::to_string(*o.overrides.steps));
  if (o.overrides.speed_kmh) add("--speed-kmh", fmt::format("{}", *o.overrides.speed_kmh));
  add("--mc-run", std::to_string(o.overrides.mc_run));
  if (o.overrides.exchange) add("--exchange", std::string(to_string(*o.overrides.exchange)));
  if (o.overrides.fanout) add("--fanout", std::to_string(*o.overrides.fanout));
  if (o.overrides.aircraft) add("--aircraft", std::to_string(*o.overrides.aircraft));
  if (o.overrides.associator) add("--associator", *o.overrides.associator);
  if (o.qos_file) add("--qos", *o.qos_file);
  if (o.secure_dir) add("--secure", *o.secure_dir);
  add("--discovery-timeout", fmt::format("{}", o.discovery_timeout_s));
  add("--idle-timeout", fmt::format("{}", o.idle_timeout_s));
  add("--realtime-deadline-ms", fmt::format("{}", o.realtime_deadline_ms));
  add("--round-deadline-ms", fmt::format("{}", o.round_deadline_ms));
  for (std::string& a : loss_arguments(o.loss, o.best_effort)) args.push_back(std::move(a));
  for (std::string& a : delay_arguments(o.delay)) args.push_back(std::move(a));
  if (o.refusion_lag != 0) add("--refusion-lag", std::to_string(o.refusion_lag));
  if (o.gate.enabled()) add("--nis-gate", fmt::format("{}", o.gate.probability()));
  for (std::string& a : network_arguments(o.network)) args.push_back(std::move(a));
  if (!o.asterix_out.empty()) add("--asterix-out", o.asterix_out);
  if (!o.asterix_replay.empty()) add("--asterix-replay", o.asterix_replay);
  if (!o.asterix_in.empty()) {
    add("--asterix-in", o.asterix_in);
    add("--asterix-in-wait-ms", fmt::format("{}", o.asterix_in_wait_ms));
  }
  add("--log-level", o.log_level);
  return args;
}

void add_loss_options(CLI::App& app, LinkLoss& loss, bool& best_effort) {
  app.add_option("--loss", loss.probability,
                 "Drop each received increment and measurement with this probability (per link, "
                 "seeded: a rerun loses the same samples)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option_function<std::string>(
         "--loss-steps",
         [&loss](const std::string& text) {
           // "A:B": steps A (inclusive) to B (exclusive).
           const auto steps = parse_number_pair(text, ':');
           if (!steps || steps->first >= steps->second) {
             throw CLI::ValidationError("--loss-steps",
                                        "expected A:B with A < B (steps A to B-1), got " + text);
           }
           std::tie(loss.first_step, loss.end_step) = *steps;
         },
         "Apply --loss only to steps A to B-1, as A:B (default: every step)")
      ->type_name("A:B");
  app.add_option("--loss-seed", loss.seed, "Seed of the simulated loss and delay")
      ->capture_default_str();
  app.add_flag("--best-effort", best_effort,
               "Increments and measurements travel BEST_EFFORT: lost datagrams are not repaired");
}

void add_delay_options(CLI::App& app, LinkDelay& delay) {
  app.add_option("--link-delay-ms", delay.delay_ms,
                 "Hold each received increment and measurement this many ms on its link "
                 "(seeded by --loss-seed: a rerun delays the same samples alike)")
      ->check(non_negative_number());
  app.add_option("--link-jitter-ms", delay.jitter_ms,
                 "Vary each link delay uniformly by up to this many ms either way (never below "
                 "0): samples arrive late and out of order")
      ->check(non_negative_number());
}

void add_refusion_option(CLI::App& app, std::size_t& lag) {
  app.add_option("--refusion-lag", lag,
                 "Keep late increments for this many closed rounds and fuse those rounds again "
                 "(fixed-lag re-fusion; 0: a late sample is refused as stale)")
      ->check(whole_number_in(0, static_cast<std::int64_t>(kMaxRefusionLag)))
      ->capture_default_str();
}

std::vector<std::string> delay_arguments(const LinkDelay& delay) {
  if (!delay.enabled()) return {};
  return {"--link-delay-ms", fmt::format("{}", delay.delay_ms), "--link-jitter-ms",
          fmt::format("{}", delay.jitter_ms)};
}

std::optional<std::pair<std::uint64_t, std::uint64_t>> parse_number_pair(std::string_view text,
                                                                         char separator) {
  // from_chars, unlike stoull, takes no sign and no leading space, and says where it stopped.
  const auto number = [](std::string_view digits) -> std::optional<std::uint64_t> {
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error != std::errc() || end != digits.data() + digits.size() || digits.empty()) {
      return std::nullopt;
    }
    return value;
  };
  const auto at = text.find(separator);
  if (at == std::string_view::npos) return std::nullopt;
  const auto first = number(text.substr(0, at));
  const auto second = number(text.substr(at + 1));
  if (!first || !second) return std::nullopt;
  return std::pair{*first, *second};
}

void add_nis_gate_option(CLI::App& app, NisGate& gate) {
  app.add_option_function<double>(
         "--nis-gate",
         [&gate](double probability) {
           if (!(probability > 0.0 && probability < 1.0)) {
             throw CLI::ValidationError("--nis-gate",
                                        "expected a probability in (0, 1), e.g. 0.9999");
           }
           gate = NisGate::at_probability(probability);
         },
         "Refuse a measurement whose NIS exceeds the chi^2 quantile at this probability (as "
         "many degrees of freedom as its sensor measures), e.g. 0.9999 (default: no gate)")
      ->type_name("P");
}

std::vector<std::string> loss_arguments(const LinkLoss& loss, bool best_effort) {
  std::vector<std::string> args;
  if (loss.probability > 0.0) {
    args = {"--loss", fmt::format("{}", loss.probability)};
    if (loss.first_step != 0 || loss.end_step != LinkLoss{}.end_step) {
      args.push_back("--loss-steps");
      args.push_back(fmt::format("{}:{}", loss.first_step, loss.end_step));
    }
  }
  if (loss.seed != LinkLoss{}.seed) {  // the delay draws with it too
    args.push_back("--loss-seed");
    args.push_back(std::to_string(loss.seed));
  }
  if (best_effort) args.push_back("--best-effort");
  return args;
}

}  // namespace skyfuse::options

namespace skyfuse::options {

int run_node(const std::function<int()>& body) {
  try {
    return body();
  } catch (const std::invalid_argument& e) {
    spdlog::error("{}", e.what());
    return kExitUsage;
  } catch (const ConfigError& e) {
    spdlog::error("{}", e.what());
    return kExitUsage;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return kExitError;
  }
}

}  // namespace skyfuse::options
