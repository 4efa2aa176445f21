#include "run/run_nodes.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "report/output_files.hpp"
#include "run/execute_run.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/transport/security_folder.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {

std::string run_scenario_text(const RunOptions& o) {
  const std::string& path = o.node.scenario_path;
  return path.empty() ? std::string(default_scenario_yaml()) : read_scenario_text(path);
}

std::filesystem::path write_run_scenario(const RunOptions& o) {
  const std::filesystem::path out(o.out_dir);
  std::filesystem::create_directories(out);
  const std::filesystem::path file = std::filesystem::absolute(out / "scenario.yaml");
  write_file_atomically(file, run_scenario_text(o));
  return file;
}

options::NodeOptions node_options_for(const RunOptions& o, const options::NetworkOptions& network,
                                      const std::filesystem::path& scenario_file,
                                      std::uint64_t run_id, double discovery_timeout_s) {
  options::NodeOptions child = o.node;
  child.network = network;
  child.scenario_path = scenario_file.string();
  child.run_id = run_id;
  child.discovery_timeout_s = discovery_timeout_s;
  child.idle_timeout_s = node_idle_timeout_s(o);
  child.log_level = o.verbose ? "info" : "warn";
  if (child.secure_dir) child.secure_dir = std::filesystem::absolute(*child.secure_dir).string();
  return child;
}

void check_before_start(const RunOptions& o, const std::vector<int>& ids, int steps) {
  check_station_events(o, ids, steps);
  Placement::check(o, ids.size());
  if (o.node.secure_dir) {  // every node's identity checked here: one message instead of M + 1
    transport::SecurityFolder{*o.node.secure_dir}.check(transport::run_identities(ids));
  }
}

RunNodes::RunNodes(const RunOptions& o, const Placement& placement, std::vector<int> ids,
                   NodeArguments arguments, std::vector<std::string> station_extra)
    : options_(o),
      placement_(placement),
      ids_(std::move(ids)),
      arguments_(std::move(arguments)),
      station_extra_(std::move(station_extra)),
      groups_(ids_.size(), static_cast<std::size_t>(o.stations_per_process)),
      namespace_members_{{-1, getpid()}} {}

void RunNodes::spawn(std::size_t process, std::vector<std::string> argv, const std::string& name) {
  const auto [network, netns] = placement_.of(process);
  const std::vector<std::string> common = arguments_(network);
  argv.insert(argv.end(), common.begin(), common.end());
  namespace_members_.try_emplace(netns, children_.spawn(name, argv, netns));
}

void RunNodes::spawn_stations(std::size_t process, std::optional<std::uint64_t> rejoin_step) {
  const std::vector<int> group = groups_.ids_of(process, ids_);
  std::vector<std::string> argv = id_arguments(group);
  argv.insert(argv.begin(), (executable_dir() / "skyfuse-station").string());
  argv.insert(argv.end(), station_extra_.begin(), station_extra_.end());
  if (rejoin_step) {
    argv.push_back("--rejoin-at-step");
    argv.push_back(std::to_string(*rejoin_step));
  }
  spawn(process, std::move(argv), process_name(group));
}

void RunNodes::start() {
  if (options_.external) return;
  spawn(0, {(executable_dir() / "skyfuse-center").string()}, node_name(kCenterNodeId));
  for (std::size_t p = 1; p < groups_.processes(); ++p) spawn_stations(p, std::nullopt);
}

void RunNodes::kill_station(int id) {
  children_.kill_now(node_name(id));
}

void RunNodes::restart_station(int id, std::uint64_t step) {
  spawn_stations(groups_.process_of_id(id, ids_), step);
}

void RunNodes::check() {
  if (transport::shutdown_requested()) {
    throw RunAborted(fmt::format("interrupted by signal {}", transport::shutdown_signal()),
                     StopCause::kInterrupted);
  }
  for (const ChildExit& e : children_.poll()) {
    if (!e.success()) throw RunAborted(e.describe(), StopCause::kNodeFailed);
  }
}

std::vector<pid_t> RunNodes::run_processes() const {
  std::vector<pid_t> processes = children_.pids();
  processes.push_back(getpid());
  return processes;
}

KernelSnapshot RunNodes::kernel_snapshot() {
  std::vector<pid_t> one_per_namespace;
  for (const auto& [netns, pid] : namespace_members_) one_per_namespace.push_back(pid);
  KernelSnapshot snapshot = take_snapshot(run_processes(), one_per_namespace);
  // A node that left between two snapshots keeps its CPU time in the count.
  snapshot.cpu_s += children_.reaped_cpu_s();
  return snapshot;
}

double node_idle_timeout_s(const RunOptions& o) {
  // A node waits well past the harness's own round timeout before it gives up on the run.
  return std::max(30.0, 3.0 * o.round_timeout_s);
}

QuietWait RunNodes::wait_until_quiet() {
  // The nodes wait for the first tick as long as their discovery or idle limit, whichever is
  // longer (NodeOptions::first_tick_timeout): the wait for quiet ends well before that, so that
  // a start that never goes quiet (a secure pair stuck in its handshake) meets round 0, which
  // says so, rather than a node that gave up first.
  const double first_tick_s = std::max(discovery_timeout_s(options_, static_cast<int>(ids_.size())),
                                       node_idle_timeout_s(options_));
  const auto limit = std::min<std::chrono::milliseconds>(
      kSettleLimit, std::chrono::milliseconds(
                        std::llround(1e3 * std::max(0.0, first_tick_s - kFirstTickMarginS))));
  return harness::wait_until_quiet(
      [&] {
        return std::optional<double>(take_snapshot(run_processes(), {}).cpu_s +
                                     children_.reaped_cpu_s());
      },
      quiet_cores(groups_.processes() + 1), limit,  // and the harness
      [&] {
        check();
        return true;
      });
}

double RunNodes::peak_resident_mib() const {
  std::uint64_t peak_kib = 0;
  for (pid_t pid : children_.pids()) {
    peak_kib = std::max(peak_kib, peak_resident_kib(pid).value_or(0));
  }
  return static_cast<double>(peak_kib) / 1024.0;
}

void RunNodes::finish(std::chrono::milliseconds wait, bool stopped) {
  if (!children_.wait_all(wait)) {
    spdlog::warn("{} node process(es) still running {} s after the {}; terminating",
                 children_.alive(), std::chrono::duration<double>(wait).count(),
                 stopped ? "run stopped" : "last step");
  }
  children_.terminate_all(std::chrono::seconds(2));
  // A node that fails during the run ends it (check()), so these exits came after every round
  // was recorded (nodes leave without their participant's goodbye so that Fast DDS's teardown
  // race cannot abort them: transport/node_presence.hpp).
  for (const ChildExit& e : children_.exited()) {
    if (!e.success()) {
      spdlog::warn("{} after the {}; every round is recorded", e.describe(),
                   stopped ? "run stopped" : "last round");
    }
  }
}

void RunNodes::terminate() {
  children_.terminate_all(std::chrono::seconds(2));
}

std::map<std::string, std::string> RunNodes::exits() const {
  std::map<std::string, std::string> out;
  for (const ChildExit& e : children_.exited()) out[e.name] = e.outcome();
  return out;
}

}  // namespace skyfuse::harness
