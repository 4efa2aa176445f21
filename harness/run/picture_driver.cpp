#include "run/picture_driver.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "run/run_aborted.hpp"
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
      roster_(config, run_id, ids_, std::move(stop_check)),
      rounds_(roster_.node().make_reader<wire::PictureRound>()) {
  roster_.wait_set().attach(rounds_);
  roster_.expect_matched(
      "picture writers", [this] { return rounds_.matched(); }, static_cast<int>(ids_.size()));
}

std::vector<wire::PictureRound> PictureDriver::run_round(std::uint32_t k,
                                                         std::chrono::milliseconds timeout) {
  const auto sent = Clock::now();
  roster_.send_tick(k);
  auto last_sent = sent;
  std::map<int, wire::PictureRound> got;
  const std::size_t up = roster_.nodes_up();
  while (got.size() < up) {
    wire::PictureRound round;
    while (rounds_.take(round)) {
      const bool ours = round.run_id() == run_id_ && round.step() == k &&
                        std::binary_search(ids_.begin(), ids_.end(), round.source_id());
      if (ours && !roster_.is_down(round.source_id())) {
        got.insert_or_assign(round.source_id(), std::move(round));
      }
    }
    if (got.size() == up) break;
    roster_.check();
    const auto now = Clock::now();
    if (now - sent >= timeout) {
      std::vector<int> missing;
      for (int id : ids_) {
        if (!got.contains(id) && !roster_.is_down(id)) missing.push_back(id);
      }
      throw RunAborted(
          fmt::format("step {}: no picture from node(s) {} within {:.1f} s", k,
                      fmt::join(missing, ", "), std::chrono::duration<double>(timeout).count()),
          StopCause::kRoundTimeout);
    }
    if (now - last_sent >= kTickRepeat) {
      roster_.send_tick(k);
      last_sent = now;
    }
    roster_.wait(kPollSlice);
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
  roster_.send_start(epoch_ns);
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
    roster_.check();
    roster_.wait(std::chrono::milliseconds(5));
  }
}

}  // namespace skyfuse::harness
