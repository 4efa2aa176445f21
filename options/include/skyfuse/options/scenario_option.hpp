#pragma once
/// \file
/// The `--scenario FILE` option, one definition for the nodes and every `skyfuse` command that
/// runs a scenario. Kept apart from node_options.hpp so that commands without DDS do not
/// compile Fast DDS headers for it.

#include <CLI/App.hpp>
#include <string>

namespace skyfuse::options {

/// `--scenario FILE` into `path`; left empty, it means the embedded paper000 scenario
/// (load_scenario_or_default reads it either way).
void add_scenario_option(CLI::App& app, std::string& path);

}  // namespace skyfuse::options
