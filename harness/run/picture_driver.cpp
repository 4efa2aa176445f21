#include "run/picture_driver.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "run/lockstep_driver.hpp"
#include "skyfuse/transport/realtime_schedule.hpp"

namespace skyfuse::harness {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kPollSlice = std::chrono::milliseconds(50);
// A station that has not matched the tick writer when the first copy went out gets another.
constexpr auto kTickRepeat = std::chrono::milliseconds(50);

}  // namespace

PictureDriver::PictureDriver(const transport::NodeConfig& config, std::uint64_t run_id,
                             std::vector<int> ids, std::function<void()> stop_check)
    : run_id_(run_id),
      ids_(std::move(ids)),
      stop_check_(std::move(stop_check)),
      node_(config),
      ticks_(node_.make_writer<wire::Tick>()),
      rounds_(node_.make_reader<wire::PictureRound>()),
      statuses_(node_.make_reader<wire::StationStatus>()) {
  wait_set_.attach(rounds_);
  wait_set_.attach(statuses_);
}

void PictureDriver::wait_until_joined(std::chrono::milliseconds timeout) {
  const auto m = static_cast<int>(ids_.size());
  const auto start = Clock::now();
  while (true) {
    check();
    if (ready_.size() == ids_.size() && ticks_.matched() >= m && rounds_.matched() >= m) return;
    if (Clock::now() - start >= timeout) {
      std::vector<int> missing;
      for (int id : ids_) {
        if (!ready_.contains(id)) missing.push_back(id);
      }
      throw RunAborted(
          fmt::format("discovery timed out after {:.1f} s; stations not ready: "
                      "{}; tick readers {}/{}, picture writers {}/{}",
                      std::chrono::duration<double>(timeout).count(), fmt::join(missing, ", "),
                      ticks_.matched(), m, rounds_.matched(), m));
    }
    wait_set_.wait(std::chrono::milliseconds(10));
  }
}

std::vector<wire::PictureRound> PictureDriver::run_round(std::uint32_t k,
                                                         std::chrono::milliseconds timeout) {
  wire::Tick tick;
  tick.run_id(run_id_);
  tick.step(k);
  tick.stop(false);
  const auto sent = Clock::now();
  ticks_.write(tick);
  auto last_sent = sent;
  std::map<int, wire::PictureRound> got;
  const std::size_t up = ids_.size() - down_.size();
  while (got.size() < up) {
    wire::PictureRound round;
    while (rounds_.take(round)) {
      const bool ours = round.run_id() == run_id_ && round.step() == k &&
                        std::binary_search(ids_.begin(), ids_.end(), round.source_id());
      if (ours && !down_.contains(round.source_id())) {
        got.insert_or_assign(round.source_id(), std::move(round));
      }
    }
    if (got.size() == up) break;
    check();
    const auto now = Clock::now();
    if (now - sent >= timeout) {
      std::vector<int> missing;
      for (int id : ids_) {
        if (!got.contains(id) && !down_.contains(id)) missing.push_back(id);
      }
      throw RunAborted(
          fmt::format("step {}: no picture from node(s) {} within {:.1f} s", k,
                      fmt::join(missing, ", "), std::chrono::duration<double>(timeout).count()),
          StopCause::kRoundTimeout);
    }
    if (now - last_sent >= kTickRepeat) {
      ticks_.write(tick);
      last_sent = now;
    }
    wait_set_.wait(kPollSlice);
  }
  std::vector<wire::PictureRound> out;  // node order: the center, then the stations up
  for (auto& [id, round] : got) out.push_back(std::move(round));
  return out;
}

void PictureDriver::run_realtime(
    int steps, double time_step_s, std::chrono::system_clock::time_point epoch,
    std::chrono::milliseconds late_after,
    const std::function<void(int, std::vector<wire::PictureRound>)>& on_round) {
  const auto epoch_ns = static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(epoch.time_since_epoch()).count());
  wire::Tick tick;
  tick.run_id(run_id_);
  tick.step(0);
  tick.stop(false);
  tick.epoch_ns(epoch_ns);
  ticks_.write(tick);
  // The rounds not handed over yet, by step; each holds the pictures that came, by node.
  std::map<int, std::map<int, wire::PictureRound>> open;
  int next = 0;  // the next round to hand over
  while (next < steps) {
    wire::PictureRound round;
    while (rounds_.take(round)) {
      const auto k = static_cast<int>(round.step());
      const bool ours = round.run_id() == run_id_ && k >= next && k < steps &&
                        std::binary_search(ids_.begin(), ids_.end(), round.source_id());
      if (ours) open[k].insert_or_assign(round.source_id(), std::move(round));
    }
    const auto now = std::chrono::system_clock::now();
    while (next < steps) {
      auto& pictures = open[next];
      const auto due =
          transport::step_start(epoch_ns, static_cast<std::uint64_t>(next + 1), time_step_s) +
          late_after;
      if (pictures.size() < ids_.size() && now < due) break;
      std::vector<wire::PictureRound> handed;
      for (auto& [id, picture] : pictures) handed.push_back(std::move(picture));
      open.erase(next);
      on_round(next, std::move(handed));
      ++next;
    }
    check();
    wait_set_.wait(std::chrono::milliseconds(5));
  }
}

void PictureDriver::set_down(int id, bool down) {
  if (down) {
    down_.insert(id);
    if (const auto it = ready_.find(id); it != ready_.end()) {
      killed_instance_[id] = it->second;
      ready_.erase(it);
    }
  } else {
    down_.erase(id);
  }
}

void PictureDriver::wait_until_ready(int id, std::chrono::milliseconds timeout) {
  const auto start = Clock::now();
  while (!ready_.contains(id)) {
    check();
    if (Clock::now() - start >= timeout) {
      throw RunAborted(fmt::format("restarted {} not ready after {:.1f} s", node_name(id),
                                   std::chrono::duration<double>(timeout).count()));
    }
    wait_set_.wait(std::chrono::milliseconds(10));
  }
}

std::map<int, PictureDriver::Finished> PictureDriver::wait_finished(
    std::chrono::milliseconds timeout) {
  const auto start = Clock::now();
  while (finished_.size() < ids_.size() - down_.size() && Clock::now() - start < timeout) {
    check();
    wait_set_.wait(std::chrono::milliseconds(10));
  }
  return finished_;
}

void PictureDriver::release() {
  wire::Tick stop;
  stop.run_id(run_id_);
  stop.stop(true);
  ticks_.write(stop);
}

void PictureDriver::check() {
  stop_check_();
  wire::StationStatus s;
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
      Finished& f = finished_[s.station_id()];
      f.resyncs = s.resyncs();
      f.lost = s.lost();
      std::copy(s.dropped().begin(), s.dropped().end(), f.dropped.begin());
    }
  }
}

}  // namespace skyfuse::harness
