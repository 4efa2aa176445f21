#pragma once
// `skyfuse run`: the system as it is meant to run - one process per station plus the fusion
// center, over DDS, driven in lock-step by this harness.

#include <CLI/App.hpp>

#include "run/execute_run.hpp"

namespace skyfuse::harness {

void add_run_command(CLI::App& app, RunOptions& options);
int run_run(const RunOptions& options);

}  // namespace skyfuse::harness
