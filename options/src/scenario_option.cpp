#include "skyfuse/options/scenario_option.hpp"

#include <CLI/CLI.hpp>

namespace skyfuse::options {

void add_scenario_option(CLI::App& app, std::string& path) {
  app.add_option("--scenario", path, "Scenario YAML file (default: the embedded paper000 scenario)")
      ->check(CLI::ExistingFile);
}

}  // namespace skyfuse::options
