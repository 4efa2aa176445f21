#pragma once
// `skyfuse bench --scale --aircraft N...`: what a round of many aircraft costs over DDS as the
// number of aircraft N and of stations M grow, flat and through the tree. For each N, M and
// exchange, a lock-step run (rounds/s, UDP
// datagrams received per round as the kernel counts them, CPU per station-round, the pictures'
// agreement) and a real-time run at the scenario's step (share of rounds with every scan fused
// in time). Writes picture_scale.json and picture_scale.csv; the rows are rewritten after each
// run, so a stopped bench keeps what it measured.

#include "scale/scale_bench.hpp"

namespace skyfuse::harness {

int run_picture_scale_bench(const ScaleBenchOptions& options);

}  // namespace skyfuse::harness
