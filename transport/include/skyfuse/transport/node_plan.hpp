#pragma once
/// \file
/// The plan a node process (or the harness) builds from its command-line options, of the kind
/// its scenario decides (sim/any_plan.hpp).

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/sim/any_plan.hpp"

namespace skyfuse::transport {

/// The run this node joins: the scenario (the options' file or the embedded default) with the
/// options' overrides, as one aircraft's plan or many's. Refuses what the nodes cannot run: a
/// secure discovery server; for one aircraft, the wire's models, a traffic file and an
/// `--asterix-out`.
AnyPlan load_any_plan(const options::NodeOptions& options);

}  // namespace skyfuse::transport
