#include "lockstep_driver.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>
#include <set>

#include "skyfuse/tracking/step_collector.hpp"
#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::harness {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kPollSlice = std::chrono::milliseconds(50);
constexpr int kCenterId = 0;

std::vector<int> with_center(std::vector<int> ids) {
  ids.push_back(kCenterId);
  return ids;
}

std::string node_name(int id) {
  return id == kCenterId ? "center" : fmt::format("station {}", id);
}

}  // namespace

struct LockstepDriver::Impl {
  Impl(const transport::NodeConfig& config, std::uint64_t run, std::vector<int> ids,
       std::function<void()> check_fn)
      : run_id(run),
        station_ids(std::move(ids)),
        check(std::move(check_fn)),
        node(config),
        ticks(node.make_writer<wire::Tick>()),
        tracks(node.make_reader<wire::TrackEstimate>()),
        measurements(node.make_reader<wire::Measurement>()),
        statuses(node.make_reader<wire::StationStatus>()),
        track_collector(with_center(station_ids)),
        measurement_collector(station_ids) {
    std::sort(station_ids.begin(), station_ids.end());
    wait_set.attach(tracks);
    wait_set.attach(measurements);
    wait_set.attach(statuses);
  }

  // Reads statuses; a node that failed ends the run with its own words.
  void read_statuses() {
    wire::StationStatus s;
    while (statuses.take(s)) {
      if (s.run_id() != run_id) continue;
      if (s.state() == wire::FAILED) {
        throw RunAborted(fmt::format("{} failed at step {}: {}", node_name(s.station_id()),
                                     s.step(), s.detail()));
      }
      if (s.state() == wire::READY) ready.insert(s.station_id());
    }
  }

  void drain_samples() {
    wire::TrackEstimate t;
    while (tracks.take(t)) {
      if (t.run_id() != run_id) continue;
      const bool is_central = t.mode() == wire::CENTRAL;
      if (is_central != (t.source_id() == kCenterId)) continue;
      track_collector.offer(t.step(), t.source_id(), transport::from_wire(t));
    }
    wire::Measurement m;
    while (measurements.take(m)) {
      if (m.run_id() != run_id) continue;
      measurement_collector.offer(m.step(), m.station_id(), Vector3(m.z()[0], m.z()[1], m.z()[2]));
    }
  }

  std::uint64_t run_id;
  std::vector<int> station_ids;
  std::function<void()> check;
  transport::DdsNode node;
  transport::Writer<wire::Tick> ticks;
  transport::Reader<wire::TrackEstimate> tracks;
  transport::Reader<wire::Measurement> measurements;
  transport::Reader<wire::StationStatus> statuses;
  transport::ReaderWaitSet wait_set;
  StepCollector<GaussianState<9>> track_collector;
  StepCollector<Vector3> measurement_collector;
  std::set<int> ready;
};

LockstepDriver::LockstepDriver(const transport::NodeConfig& config, std::uint64_t run_id,
                               std::vector<int> station_ids, std::function<void()> check)
    : impl_(std::make_unique<Impl>(config, run_id, std::move(station_ids), std::move(check))) {}

LockstepDriver::~LockstepDriver() = default;

std::chrono::nanoseconds LockstepDriver::wait_until_joined(std::chrono::milliseconds timeout) {
  Impl& d = *impl_;
  const int m = static_cast<int>(d.station_ids.size());
  const auto start = Clock::now();
  const auto all_ready = [&] {
    if (!d.ready.contains(kCenterId)) return false;
    return std::all_of(d.station_ids.begin(), d.station_ids.end(),
                       [&](int id) { return d.ready.contains(id); });
  };
  while (true) {
    d.check();
    d.read_statuses();
    const bool matched =
        d.ticks.matched() >= m + 1 && d.tracks.matched() >= m + 1 && d.measurements.matched() >= m;
    if (matched && all_ready()) return Clock::now() - start;
    if (Clock::now() - start >= timeout) {
      std::vector<std::string> missing;
      for (int id : with_center(d.station_ids)) {
        if (!d.ready.contains(id)) missing.push_back(node_name(id));
      }
      throw RunAborted(fmt::format(
          "discovery timed out after {:.1f} s; not ready: {}; tick readers {}/{}, track "
          "writers {}/{}, measurement writers {}/{}",
          std::chrono::duration<double>(timeout).count(),
          missing.empty() ? "none" : fmt::format("{}", fmt::join(missing, ", ")), d.ticks.matched(),
          m + 1, d.tracks.matched(), m + 1, d.measurements.matched(), m));
    }
    d.wait_set.wait(std::chrono::milliseconds(10));
  }
}

RoundRecord LockstepDriver::run_round(std::uint64_t k, std::chrono::milliseconds timeout) {
  Impl& d = *impl_;
  wire::Tick tick;
  tick.run_id(d.run_id);
  tick.step(static_cast<std::uint32_t>(k));
  tick.stop(false);
  const auto sent = Clock::now();
  d.ticks.write(tick);

  while (true) {
    d.drain_samples();
    if (d.track_collector.complete() && d.measurement_collector.complete()) break;
    d.check();
    d.read_statuses();
    if (Clock::now() - sent >= timeout) {
      std::vector<std::string> missing;
      for (int id : d.track_collector.missing()) missing.push_back(node_name(id));
      throw RunAborted(fmt::format("round {} timed out after {:.1f} s waiting for tracks of {}", k,
                                   std::chrono::duration<double>(timeout).count(),
                                   fmt::join(missing, ", ")));
    }
    d.wait_set.wait(kPollSlice);
  }

  RoundRecord record;
  record.step = k;
  record.latency = Clock::now() - sent;
  const auto tracks = d.track_collector.payloads();  // ascending id: the center (0) first
  record.central = tracks.front();
  record.peers.assign(tracks.begin() + 1, tracks.end());
  const auto z = d.measurement_collector.payloads();
  record.measurements.assign(z.begin(), z.end());
  d.track_collector.advance();
  d.measurement_collector.advance();
  return record;
}

void LockstepDriver::stop() {
  wire::Tick tick;
  tick.run_id(impl_->run_id);
  tick.step(0);
  tick.stop(true);
  try {
    impl_->ticks.write(tick);
    impl_->ticks.wait_acknowledged(std::chrono::milliseconds(500));
  } catch (const transport::DdsError&) {
    // Best effort: the children are terminated by signal right after.
  }
}

}  // namespace skyfuse::harness
