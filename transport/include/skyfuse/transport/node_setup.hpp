#pragma once
/// \file
/// What a node process builds from its command-line options: its DDS participant's settings
/// and its run plan (refusing a configuration the wire cannot carry yet).

#include <string>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/transport/node_config.hpp"

namespace skyfuse::transport {

/// The participant settings of the node called `name` (its security identity follows the
/// name).
NodeConfig node_config(const options::NodeOptions& options, const std::string& name);

/// The run this node joins: the scenario with the options' overrides.
RunPlan load_plan(const options::NodeOptions& options);

}  // namespace skyfuse::transport
