#pragma once
/// \file
/// The node options a run's filter takes: its part states what it refuses (filters/parts/), and
/// a node or `skyfuse run` refuses such options before anything starts. Every registered motion
/// model and sensor runs over DDS: the wire carries any state dimension up to 16.

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse::options {

/// Settles the run's exchange and checks what the filter takes: the tree that `auto` chose by
/// size goes back to flat for a run with simulated loss, link delay or a re-fusion lag (the
/// tree keeps its guarantees through loss and delay, but flat peers stay closer under loss and
/// flat rounds are faster over delayed links, one hop instead of three; the tree takes no lag:
/// docs/performance.md#the-default-exchange). Then throws
/// std::invalid_argument, naming the option and the filter, for a re-fusion lag or a NIS gate
/// that the scenario's filter does not take, and for an exchange the nodes do not run. The
/// harness and every node call it on their plans alike.
void settle_exchange(Scenario& scenario, const NodeOptions& node);

}  // namespace skyfuse::options
