#pragma once
/// \file
/// The node options a run's filter takes: its part states what it refuses (filters/parts/), and
/// a node or `skyfuse run` refuses such options before anything starts. Every registered motion
/// model and sensor runs over DDS: the wire carries any state dimension up to 16.

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse::options {

/// Throws std::invalid_argument, naming the option and the filter, for a re-fusion lag or a NIS
/// gate that the scenario's filter does not take, and for an exchange the nodes do not run.
void require_filter_takes(const Scenario& scenario, const NodeOptions& node);

}  // namespace skyfuse::options
