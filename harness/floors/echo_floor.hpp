#pragma once
// The bare Fast DDS lock-step floors: a commander publishes Tick{k} and waits until each of M
// echo processes has answered, then ticks k+1. Same participant setup and QoS as a skyfuse
// run, no estimation: the best round rate a run could reach here. In the all-to-all floor each
// echo first exchanges an increment-sized sample with the others, as stations do: what the
// peer-to-peer exchange alone costs.

#include <chrono>

#include "run/child_processes.hpp"
#include "skyfuse/transport/node_config.hpp"

namespace skyfuse::harness {

struct FloorResult {
  double rounds_per_s = 0.0;
  double latency_us_p50 = 0.0;
  double latency_us_p99 = 0.0;
  double latency_us_max = 0.0;
  double discovery_s = 0.0;
};

enum class FloorKind {
  kEcho,      ///< tick -> M echoes -> commander
  kAllToAll,  ///< tick -> M echoes, each sample to every other echo, then -> commander
};

FloorResult measure_floor(const transport::NodeConfig& config, int nodes, int rounds,
                          std::chrono::milliseconds timeout, FloorKind kind);

}  // namespace skyfuse::harness
