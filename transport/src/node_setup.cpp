#include "skyfuse/transport/node_setup.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "skyfuse/options/filter_options.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/transport/node_plan.hpp"
#include "skyfuse/transport/security_folder.hpp"

namespace skyfuse::transport {

NodeConfig node_config(const options::NodeOptions& options, const std::string& name) {
  NodeConfig config;
  config.domain_id = options.domain;
  config.name = name;
  if (options.qos_file) config.qos_file = *options.qos_file;
  config.best_effort_data = options.best_effort;
  config.network = options.network;
  if (options.overrides.stations) {
    config.network.lease_s = options::lease_seconds(*options.overrides.stations);
  }
  if (options.secure_dir) {
    config.security = SecurityConfig{*options.secure_dir, identity_for_participant(name)};
  }
  return config;
}

AnyPlan load_any_plan(const options::NodeOptions& options) {
  if (options.secure_dir && options.network.discovery_server) {
    throw std::invalid_argument(kSecureDiscoveryServerRefusal);
  }
  AnyPlan plan = make_plan(load_scenario_or_default(options.scenario_path), options.overrides);
  if (auto* one = std::get_if<RunPlan>(&plan)) {
    if (!options.traffic_file.empty()) {
      throw std::invalid_argument(fmt::format(
          "--traffic-file: scenario '{}' has one target; the option is for one with 'traffic'",
          one->scenario.name));
    }
    if (!options.asterix_out.empty()) {
      throw std::invalid_argument(fmt::format(
          "--asterix-out: scenario '{}' has one target, and one aircraft's run has no system "
          "tracks to send; the option is for one with 'traffic'",
          one->scenario.name));
    }
    if (!options.asterix_replay.empty()) {
      throw std::invalid_argument(fmt::format(
          "--asterix-replay: scenario '{}' has one target; plots and reports feed a picture, "
          "a scenario with 'traffic'",
          one->scenario.name));
    }
    if (!options.asterix_in.empty()) {
      throw std::invalid_argument(fmt::format(
          "--asterix-in: scenario '{}' has one target; plots and reports feed a picture, "
          "a scenario with 'traffic'",
          one->scenario.name));
    }
    options::settle_exchange(one->scenario, options);
  }
  return plan;
}

}  // namespace skyfuse::transport
