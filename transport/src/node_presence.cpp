#include "skyfuse/transport/node_presence.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <thread>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::transport {

NodePresence::NodePresence(DdsNode& node, std::uint64_t run_id, int node_id)
    : node_(node),
      run_id_(run_id),
      node_id_(node_id),
      instance_(std::random_device{}() ^
                (static_cast<std::uint64_t>(std::random_device{}()) << 32) ^
                static_cast<std::uint64_t>(getpid())),
      started_ns_(
          static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                         std::chrono::system_clock::now().time_since_epoch())
                                         .count())),
      writer_(node.make_writer<wire::StationStatus>()),
      refusal_reports_(node.make_writer<wire::StationStatus>({kRefusalReportsPartition})),
      reader_(node.make_reader<wire::StationStatus>()) {}

void NodePresence::announce(wire::NodeState state, std::uint32_t step, const std::string& detail) {
  writer_.write(status(state, step, detail));
}

void NodePresence::report_refusals(std::uint32_t step) {
  refusal_reports_.write(status(wire::READY, step, {}));
}

wire::StationStatus NodePresence::status(wire::NodeState state, std::uint32_t step,
                                         const std::string& detail) const {
  wire::StationStatus status;
  status.run_id(run_id_);
  status.station_id(node_id_);
  status.instance(instance_);
  status.started_ns(started_ns_);
  status.state(state);
  status.step(step);
  status.detail(detail.substr(0, 500));
  static_assert(kDropKinds == wire::kDropKinds, "the wire's drop kinds are DropKind's");
  std::copy(drops_.begin(), drops_.end(), status.dropped().begin());
  status.lost(lost_);
  status.resyncs(resyncs_);
  status.late_used(late_used_);
  status.participants_known(static_cast<std::uint32_t>(node_.participants_known()));
  return status;
}

std::optional<std::string> NodePresence::find_older_twin() {
  wire::StationStatus status;
  while (reader_.take(status)) {
    if (status.run_id() != run_id_ || status.station_id() != node_id_ ||
        status.instance() == instance_) {
      continue;
    }
    const bool other_is_older =
        status.started_ns() < started_ns_ ||
        (status.started_ns() == started_ns_ && status.instance() < instance_);
    if (other_is_older && !older_twin_) {
      older_twin_ = fmt::format("instance {:016x}, started {:.3f} s earlier", status.instance(),
                                static_cast<double>(started_ns_ - status.started_ns()) * 1e-9);
    }
  }
  return older_twin_;
}

}  // namespace skyfuse::transport

namespace skyfuse::transport {

JoinResult join_run(NodePresence& presence, const std::function<bool()>& all_matched,
                    const std::function<std::string()>& describe_missing,
                    std::chrono::milliseconds timeout) {
  // Durable samples follow discovery by a few milliseconds; this margin lets them land.
  constexpr auto kStatusSettle = std::chrono::milliseconds(200);
  // Every node polls while all of them discover each other, on a machine whose CPU is what
  // discovery lacks, so the poll is kept coarse. Whether 20 ms rather than 5 ms shortens
  // discovery was not shown: at M = 64 (66 processes on 2 cores), one run each back to back,
  // 5 ms took 23 s and 20 ms 26 s, the other run of each failing; earlier comparisons
  // (28-44 s against 16-26 s) had another change mixed in. Up to M = 8 it takes 0.3-0.4 s.
  constexpr auto kJoinPoll = std::chrono::milliseconds(20);
  presence.announce(wire::STARTING);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::optional<std::chrono::steady_clock::time_point> matched_at;
  while (true) {
    if (shutdown_requested()) return {JoinOutcome::kShutdown, {}};
    if (auto twin = presence.find_older_twin()) return {JoinOutcome::kDuplicate, *twin};
    const auto now = std::chrono::steady_clock::now();
    if (!matched_at && all_matched()) matched_at = now;
    if (matched_at && now - *matched_at >= kStatusSettle) break;
    if (!matched_at && now >= deadline) return {JoinOutcome::kTimedOut, describe_missing()};
    std::this_thread::sleep_for(kJoinPoll);
  }
  presence.announce(wire::READY);
  return {JoinOutcome::kJoined, {}};
}

void leave_without_goodbye(int code) {
  spdlog::shutdown();  // flushes every sink
  std::fflush(nullptr);
  std::_Exit(code);
}

std::optional<int> exit_code_if_duplicate(NodePresence& presence, const std::string& who,
                                          std::uint64_t run_id) {
  if (auto twin = presence.find_older_twin()) {
    return exit_code_unless_joined({JoinOutcome::kDuplicate, *twin}, presence, who, run_id, 0.0);
  }
  return std::nullopt;
}

std::optional<int> exit_code_unless_joined(const JoinResult& result, NodePresence& presence,
                                           const std::string& who, std::uint64_t run_id,
                                           double timeout_s) {
  switch (result.outcome) {
    case JoinOutcome::kJoined:
      return std::nullopt;
    case JoinOutcome::kDuplicate:
      spdlog::error("{} is already running in run {} ({}); refusing to start a second", who, run_id,
                    result.detail);
      return options::kExitDuplicateId;
    case JoinOutcome::kTimedOut:
      spdlog::error("discovery timed out after {} s: {}", timeout_s, result.detail);
      presence.announce(wire::FAILED, 0, "discovery timed out: " + result.detail);
      return options::kExitDiscoveryTimeout;
    case JoinOutcome::kShutdown:
      return 128 + shutdown_signal();
  }
  return options::kExitError;
}

}  // namespace skyfuse::transport
