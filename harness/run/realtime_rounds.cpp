#include "run/realtime_rounds.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "skyfuse/core/sorted_ids.hpp"

namespace skyfuse::harness {

RealtimeRounds::RealtimeRounds(std::vector<int> station_ids, std::uint64_t steps)
    : station_ids_(std::move(station_ids)), steps_(steps) {}

std::optional<std::size_t> RealtimeRounds::slot(int node) const {
  if (node == kCenterNodeId) return 0;
  const auto station = position_of(station_ids_, node);
  if (!station) return std::nullopt;
  return *station + 1;
}

std::optional<DropKind> RealtimeRounds::check_step(std::uint64_t step) const {
  if (step >= steps_) return DropKind::kFutureStep;
  if (step < handed_over_) return DropKind::kStaleStep;
  return std::nullopt;
}

RealtimeRounds::Pending& RealtimeRounds::pending_step(std::uint64_t step) {
  const auto [it, inserted] = pending_.try_emplace(step);
  if (inserted) {
    const std::size_t m = station_ids_.size();
    it->second.record.step = step;
    it->second.record.peers.resize(m);
    it->second.record.measurements.resize(m);
    it->second.record.track_age_us.assign(m + 1, 0.0);
  }
  return it->second;
}

std::optional<DropKind> RealtimeRounds::check_track(int source, std::uint64_t step) const {
  if (!slot(source)) return DropKind::kUnknownStation;
  return check_step(step);
}

std::optional<DropKind> RealtimeRounds::offer_track(int source, std::uint64_t step,
                                                    ReceivedTrack track, double age_us) {
  if (const auto why = check_track(source, step)) return why;
  const std::size_t i = *slot(source);
  Pending& p = pending_step(step);
  std::optional<ReceivedTrack>& kept = i == 0 ? p.record.central : p.record.peers[i - 1];
  if (kept) return DropKind::kDuplicate;
  if (track.contributors.size() != station_ids_.size()) p.record.all_inputs_in_time = false;
  kept = std::move(track);
  p.record.track_age_us[i] = age_us;
  ++p.tracks;
  steps_reached_ = std::max(steps_reached_, step + 1);
  return std::nullopt;
}

std::optional<DropKind> RealtimeRounds::check_measurement(int station, std::uint64_t step) const {
  const auto i = slot(station);
  if (!i || *i == 0) return DropKind::kUnknownStation;
  return check_step(step);
}

std::optional<DropKind> RealtimeRounds::offer_measurement(int station, std::uint64_t step,
                                                          const Eigen::VectorXd& z) {
  if (const auto why = check_measurement(station, step)) return why;
  Pending& p = pending_step(step);
  std::optional<Eigen::VectorXd>& kept = p.record.measurements[*slot(station) - 1];
  if (kept) return DropKind::kDuplicate;
  kept = z;
  ++p.measurements;
  return std::nullopt;
}

std::uint64_t RealtimeRounds::hand_over(std::vector<RoundRecord>& done) {
  const std::size_t m = station_ids_.size();
  const auto overtaken = [&](std::uint64_t step) {
    const auto later = pending_.find(step + kLostAfterSteps);
    return later != pending_.end() && later->second.tracks == m + 1;
  };
  while (handed_over_ < steps_) {
    const std::uint64_t step = handed_over_;
    const auto it = pending_.find(step);
    const bool complete =
        it != pending_.end() && it->second.tracks == m + 1 && it->second.measurements == m;
    if (!complete && !overtaken(step)) break;
    hand_over_next(done);
  }
  return handed_over_;
}

std::uint64_t RealtimeRounds::hand_over_rest(std::vector<RoundRecord>& done) {
  while (handed_over_ < steps_reached_) hand_over_next(done);
  return handed_over_;
}

void RealtimeRounds::hand_over_next(std::vector<RoundRecord>& done) {
  // Given up on or complete: what is missing now is lost (a step nothing arrived for at all
  // leaves empty).
  const std::size_t m = station_ids_.size();
  const std::uint64_t step = handed_over_;
  Pending& p = pending_step(step);
  RoundRecord r = std::move(p.record);
  tracks_lost_ += m + 1 - p.tracks;
  measurements_lost_ += m - p.measurements;
  if (p.tracks < m + 1) r.all_inputs_in_time = false;
  const double oldest_us = *std::max_element(r.track_age_us.begin(), r.track_age_us.end());
  r.latency = std::chrono::nanoseconds(std::llround(1e3 * oldest_us));
  done.push_back(std::move(r));
  pending_.erase(step);
  ++handed_over_;
}

}  // namespace skyfuse::harness
