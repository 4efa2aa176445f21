#include "skyfuse/transport/node_options.hpp"

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <stdexcept>

#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/transport/security_folder.hpp"

namespace skyfuse::transport {

NodeConfig NodeOptions::node_config(const std::string& name) const {
  NodeConfig config;
  config.domain_id = domain;
  config.name = name;
  if (qos_file) config.qos_file = *qos_file;
  if (secure_dir) config.security = SecurityConfig{*secure_dir, identity_for_participant(name)};
  return config;
}

RunPlan NodeOptions::load_plan() const {
  Scenario scenario =
      scenario_path.empty() ? load_default_scenario() : load_scenario_file(scenario_path);
  return make_run_plan(std::move(scenario), overrides);
}

std::chrono::milliseconds NodeOptions::discovery_timeout() const {
  return std::chrono::milliseconds(static_cast<long>(discovery_timeout_s * 1000.0));
}
std::chrono::milliseconds NodeOptions::idle_timeout() const {
  return std::chrono::milliseconds(static_cast<long>(idle_timeout_s * 1000.0));
}

void add_node_options(CLI::App& app, NodeOptions& o) {
  app.add_option("--scenario", o.scenario_path,
                 "Scenario YAML file (default: the embedded paper000 scenario)")
      ->check(CLI::ExistingFile);
  app.add_option("--domain", o.domain, "DDS domain id")
      ->check(CLI::Range(0, kMaxDomainId))
      ->capture_default_str();
  app.add_option("--run-id", o.run_id, "Run id shared by every process of the run")
      ->capture_default_str();
  app.add_option("--stations", o.overrides.stations,
                 "Number of participating stations: the first M of the scenario (default: all)")
      ->check(CLI::PositiveNumber);
  app.add_option("--steps", o.overrides.steps, "Override the scenario's number of steps")
      ->check(CLI::PositiveNumber);
  app.add_option("--speed-kmh", o.overrides.speed_kmh,
                 "Target speed (default: the first the scenario lists)")
      ->check(CLI::PositiveNumber);
  app.add_option("--mc-run", o.overrides.mc_run,
                 "Monte-Carlo run index; selects the noise realisation")
      ->capture_default_str();
  app.add_option("--qos", o.qos_file, "Fast DDS XML profiles overriding the built-in QoS")
      ->check(CLI::ExistingFile);
  app.add_option("--secure", o.secure_dir,
                 "DDS-Security: this node's identity from a folder made by `skyfuse certs`")
      ->check(CLI::ExistingDirectory);
  app.add_option("--discovery-timeout", o.discovery_timeout_s,
                 "Seconds to wait for every peer to be discovered")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--idle-timeout", o.idle_timeout_s,
                 "Seconds without progress after which the process gives up")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--realtime-deadline-ms", o.realtime_deadline_ms,
                 "Real-time mode: step on the wall clock at the scenario's dt and close each "
                 "round this many ms after it starts (0: lock-step on ticks)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--log-level", o.log_level, "trace, debug, info, warn, error")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}))
      ->capture_default_str();
}

}  // namespace skyfuse::transport

namespace skyfuse::transport {

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

}  // namespace skyfuse::transport
