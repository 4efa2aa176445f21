#include "run/node_roster.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "run/run_aborted.hpp"
#include "skyfuse/transport/refusal_reports.hpp"

namespace skyfuse::harness {
namespace {

constexpr auto kWaitSlice = std::chrono::milliseconds(10);

double seconds(std::chrono::milliseconds d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace

std::string node_name(int id) {
  return id == kCenterNodeId ? "center" : fmt::format("station {}", id);
}

NodeRoster::NodeRoster(const transport::NodeConfig& config, std::uint64_t run_id,
                       std::vector<int> ids, std::function<void()> stop_check)
    : run_id_(run_id),
      ids_(std::move(ids)),
      stop_check_(std::move(stop_check)),
      node_(config),
      ticks_(node_.make_writer<wire::Tick>()),
      statuses_(node_.make_reader<wire::StationStatus>()),
      refusal_reports_(
          node_.make_reader<wire::StationStatus>({transport::kRefusalReportsPartition})) {
  std::sort(ids_.begin(), ids_.end());
  wait_set_.attach(statuses_);
  wait_set_.attach(refusal_reports_);
  expect_matched(
      "tick readers", [this] { return ticks_.matched(); }, static_cast<int>(ids_.size()));
}

void NodeRoster::expect_matched(std::string name, std::function<int()> matched, int expected) {
  expected_.push_back({std::move(name), std::move(matched), expected});
}

void NodeRoster::wait_a_moment() {
  if (drain_) drain_();
  wait_set_.wait(kWaitSlice);
}

void NodeRoster::wait_until_joined(std::chrono::milliseconds timeout) {
  const auto start = Clock::now();
  while (true) {
    check();
    const bool all_ready =
        std::all_of(ids_.begin(), ids_.end(), [&](int id) { return ready_.contains(id); });
    const bool all_matched = std::all_of(expected_.begin(), expected_.end(), [](const Expected& e) {
      return e.matched() >= e.expected;
    });
    if (all_ready && all_matched) {
      for (int id : ids_) up_since_[id] = Clock::now();
      return;
    }
    if (Clock::now() - start >= timeout) {
      std::vector<std::string> missing;
      for (int id : ids_) {
        if (!ready_.contains(id)) missing.push_back(node_name(id));
      }
      std::vector<std::string> endpoints;
      for (const Expected& e : expected_) {
        endpoints.push_back(fmt::format("{} {}/{}", e.name, e.matched(), e.expected));
      }
      throw RunAborted(
          fmt::format("discovery timed out after {:.1f} s; not ready: {}; {}", seconds(timeout),
                      missing.empty() ? "none" : fmt::format("{}", fmt::join(missing, ", ")),
                      fmt::join(endpoints, ", ")));
    }
    wait_a_moment();
  }
}

void NodeRoster::set_down(int id, bool down) {
  if (down) {
    down_.insert(id);
    if (const auto it = ready_.find(id); it != ready_.end()) {
      killed_instance_[id] = it->second;
      ready_.erase(it);
    }
  } else {
    down_.erase(id);
    up_since_[id] = Clock::now();
  }
}

NodeRoster::Clock::time_point NodeRoster::up_since(int id) const {
  const auto it = up_since_.find(id);
  return it == up_since_.end() ? Clock::time_point{} : it->second;
}

void NodeRoster::wait_until_ready(int id, std::chrono::milliseconds timeout) {
  const auto start = Clock::now();
  while (!ready_.contains(id)) {
    check();
    if (Clock::now() - start >= timeout) {
      throw RunAborted(
          fmt::format("restarted {} not ready after {:.1f} s", node_name(id), seconds(timeout)));
    }
    wait_a_moment();
  }
}

void NodeRoster::check() {
  stop_check_();
  read_statuses();
}

void NodeRoster::read_statuses() {
  wire::StationStatus s;
  while (refusal_reports_.take(s)) {
    if (s.run_id() != run_id_ || s.state() != wire::READY) continue;
    DropCounts dropped{};
    std::copy(s.dropped().begin(), s.dropped().end(), dropped.begin());
    note_refusals(s.station_id(), s.instance(), s.step(), dropped);
  }
  while (statuses_.take(s)) {
    if (s.run_id() != run_id_) continue;
    if (s.state() == wire::FAILED) {
      throw RunAborted(
          fmt::format("{} failed at step {}: {}", node_name(s.station_id()), s.step(), s.detail()),
          StopCause::kNodeFailed);
    }
    // A killed process's own READY (durable) must not count for its replacement.
    const auto killed = killed_instance_.find(s.station_id());
    if (s.state() == wire::READY &&
        (killed == killed_instance_.end() || killed->second != s.instance())) {
      ready_[s.station_id()] = s.instance();
    }
    if (s.state() == wire::FINISHED) {
      DropCounts dropped{};
      std::copy(s.dropped().begin(), s.dropped().end(), dropped.begin());
      note_refusals(s.station_id(), s.instance(), s.step(), dropped);
      NodeCounts& counts = finished_[s.station_id()];
      counts.dropped = dropped;
      counts.lost = s.lost();
      counts.resyncs = s.resyncs();
      counts.late_used = s.late_used();
      counts.participants_known = s.participants_known();
    }
  }
}

void NodeRoster::send_tick(std::uint32_t k) {
  wire::Tick tick;
  tick.run_id(run_id_);
  tick.step(k);
  tick.stop(false);
  ticks_.write(tick);
}

void NodeRoster::send_start(std::uint64_t epoch_ns) {
  wire::Tick tick;
  tick.run_id(run_id_);
  tick.step(0);
  tick.stop(false);
  tick.epoch_ns(epoch_ns);
  ticks_.write(tick);
}

void NodeRoster::send_stop() {
  wire::Tick tick;
  tick.run_id(run_id_);
  tick.step(0);
  tick.stop(true);
  try {
    ticks_.write(tick);
    ticks_.wait_acknowledged(std::chrono::milliseconds(500));
  } catch (const transport::DdsError&) {
    // Best effort: the children are terminated by signal right after.
  }
}

bool NodeRoster::wait_until_finished(std::chrono::milliseconds timeout) {
  const auto give_up = Clock::now() + timeout;
  while (true) {
    read_statuses();
    const bool all = std::all_of(ids_.begin(), ids_.end(), [&](int id) {
      return down_.contains(id) || finished_.contains(id);
    });
    if (all) return true;
    if (Clock::now() >= give_up) return false;
    wait_a_moment();
  }
}

void NodeRoster::note_refusals(int node_id, std::uint64_t instance, std::uint64_t step,
                               const DropCounts& counts) {
  auto& [seen_instance, before] = reported_[node_id];
  if (seen_instance != instance) {  // a new process counts from zero
    seen_instance = instance;
    before = {};
  }
  // Counts only grow; a report that comes after a later status (two writers: the reports and
  // the node's last status) adds nothing.
  for (std::size_t i = 0; i < kDropKinds; ++i) {
    if (counts[i] > before[i]) {
      refusals_.push_back({node_id, step, static_cast<DropKind>(i), counts[i] - before[i]});
      before[i] = counts[i];
    }
  }
}

std::vector<Refusal> NodeRoster::take_refusals(std::uint64_t step, const DropCounts& harness_own) {
  read_statuses();
  note_refusals(kHarnessNodeId, 0, step, harness_own);
  return std::exchange(refusals_, {});
}

}  // namespace skyfuse::harness
