#include "floors/echo_floor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "report/output_files.hpp"
#include "report/statistics.hpp"
#include "run/lockstep_driver.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

FloorResult measure_floor(const transport::NodeConfig& config, int nodes, int rounds,
                          std::chrono::milliseconds timeout, FloorKind kind) {
  const std::uint64_t run_id = fresh_run_id();
  ChildProcesses children;
  transport::DdsNode node(config);
  auto ticks = node.make_writer<wire::Tick>();
  auto echoes = node.make_reader<wire::Echo>();
  auto statuses = node.make_reader<wire::StationStatus>();
  transport::ReaderWaitSet wait_set;
  wait_set.attach(echoes);
  wait_set.attach(statuses);

  const auto check = [&] {
    if (transport::shutdown_requested()) throw RunAborted("interrupted");
    for (const ChildExit& e : children.poll()) {
      if (!e.success()) throw RunAborted("floor: " + e.describe());
    }
  };
  for (int id = 1; id <= nodes; ++id) {
    std::vector<std::string> args = {helper_program("skyfuse-echo").string(),
                                     "--id",
                                     std::to_string(id),
                                     "--domain",
                                     std::to_string(config.domain_id),
                                     "--run-id",
                                     std::to_string(run_id),
                                     "--discovery-timeout",
                                     fmt::format("{}", default_discovery_timeout_s(nodes))};
    if (config.qos_file) {
      args.push_back("--qos");
      args.push_back(config.qos_file->string());
    }
    if (kind == FloorKind::kAllToAll) {
      args.push_back("--all-to-all");
      args.push_back(std::to_string(nodes));
    }
    children.spawn(fmt::format("echo {}", id), args);
  }

  FloorResult result;
  const auto start = Clock::now();
  std::set<int> ready;
  while (static_cast<int>(ready.size()) < nodes || ticks.matched() < nodes ||
         echoes.matched() < nodes) {
    check();
    wire::StationStatus s;
    while (statuses.take(s)) {
      if (s.run_id() == run_id && s.state() == wire::READY) ready.insert(s.station_id());
    }
    if (Clock::now() - start > timeout) throw RunAborted("floor: discovery timed out");
    wait_set.wait(std::chrono::milliseconds(10));
  }
  result.discovery_s = std::chrono::duration<double>(Clock::now() - start).count();

  std::vector<double> latencies;
  std::vector<bool> answered(static_cast<std::size_t>(nodes) + 1);
  wire::Tick tick;
  tick.run_id(run_id);
  tick.stop(false);
  const auto first = Clock::now();
  for (int k = 0; k < rounds; ++k) {
    std::fill(answered.begin(), answered.end(), false);
    int count = 0;
    tick.step(static_cast<std::uint32_t>(k));
    const auto sent = Clock::now();
    ticks.write(tick);
    while (count < nodes) {
      wire::Echo e;
      while (echoes.take(e)) {
        const auto id = static_cast<std::size_t>(e.node_id());
        if (e.run_id() != run_id || e.step() != static_cast<std::uint32_t>(k) || id < 1 ||
            id > static_cast<std::size_t>(nodes) || answered[id]) {
          continue;
        }
        answered[id] = true;
        ++count;
      }
      if (count == nodes) break;
      check();
      if (Clock::now() - sent > timeout)
        throw RunAborted(fmt::format("floor: round {} timed out", k));
      wait_set.wait(std::chrono::milliseconds(50));
    }
    latencies.push_back(std::chrono::duration<double, std::micro>(Clock::now() - sent).count());
  }
  const double elapsed = std::chrono::duration<double>(Clock::now() - first).count();
  tick.stop(true);
  ticks.write(tick);
  ticks.wait_acknowledged(std::chrono::milliseconds(500));
  children.wait_all(std::chrono::seconds(5));

  result.rounds_per_s = static_cast<double>(rounds) / elapsed;
  result.latency_us_p50 = percentile(latencies, 0.50);
  result.latency_us_p99 = percentile(latencies, 0.99);
  result.latency_us_max = *std::max_element(latencies.begin(), latencies.end());
  return result;
}

}  // namespace skyfuse::harness
