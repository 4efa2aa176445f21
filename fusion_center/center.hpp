#pragma once
// The center process's endpoints and round loop, compiled once: what updates its rounds is
// behind CenterRounds (center_rounds.hpp), made for the run's filter part and stations per shard
// of the filter parts.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <optional>
#include <utility>

#include "center_process.hpp"
#include "center_rounds.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/node_loop.hpp"
#include "skyfuse/transport/node_setup.hpp"

namespace skyfuse::center {

using transport::RunEnd;

// The round loop (transport/node_loop.hpp) moves the samples; this is what the center adds.
class Center {
 public:
  // The endpoints are made in a fixed order: the loop's tick and measurement readers first.
  Center(const options::NodeOptions& options, const RunPlan& plan,
         std::unique_ptr<CenterRounds> rounds)
      : options_(options),
        plan_(plan),
        rounds_(std::move(rounds)),
        node_(transport::node_config(options, "skyfuse-center")),
        loop_(node_, options, kCenterSourceId, "a fusion center", "measurement",
              plan.scenario.time_step_s),
        tracks_(node_.make_writer<wire::TrackEstimate>()) {}

  int run() {
    const int m = plan_.stations;
    auto& measurements = loop_.inputs();
    auto& ticks = loop_.ticks();
    if (const RunEnd end = loop_.join(
            [&] {
              return measurements.matched() >= m && ticks.matched() >= 1 && tracks_.matched() >= 1;
            },
            [&] {
              return fmt::format("measurement writers {}/{}, tick writer {}/1, track readers {}/1",
                                 measurements.matched(), m, ticks.matched(), tracks_.matched());
            })) {
      return *end;
    }
    spdlog::info("joined run {} with {} stations", options_.run_id, m);
    const int code = loop_.run(*this, 0, static_cast<std::uint64_t>(plan_.scenario.steps), tracks_);
    rounds_->report();
    return code;
  }

  // What the round loop asks of the center (transport::NodeProcess).

  RunEnd open_round(std::uint64_t /*k*/) { return std::nullopt; }  // it measures nothing

  std::optional<DropKind> receive(const wire::Measurement& sample,
                                  const transport::WriterId& writer) {
    return rounds_->receive(sample, writer);
  }

  bool round_complete() const { return rounds_->round_complete(); }

  // Updates round k with the measurements that arrived, screened and stacked by the round
  // rule as the in-process twin does, so both compute the same bits (and, with a re-fusion
  // lag, the rounds late measurements came for again); publishes its track and the one that
  // leaves the lag.
  RunEnd close_round(std::uint64_t k) {
    const NumericalStatus status = rounds_->close_round(
        options_.nis_gate(),
        [&](int station_id, DropKind why) { loop_.count_drop(why, station_id, k); });
    if (status != NumericalStatus::kOk) {
      return loop_.fail(k, fmt::format("step {}: stacked update failed: {}", k, to_string(status)),
                        options::kExitNumerical);
    }
    tracks_.write(rounds_->track_of(k));
    if (const auto settled = rounds_->settled_round()) tracks_.write(settled_track(*settled));
    rounds_->advance();
    return std::nullopt;
  }

  // After the last round, with a re-fusion lag: the rounds late measurements came for updated
  // again, and the final tracks of the rounds still in the lag.
  RunEnd settle(std::uint64_t steps) {
    NumericalStatus status = NumericalStatus::kOk;
    const auto [from, to] = rounds_->settle_rest(options_.nis_gate(), status);
    if (status != NumericalStatus::kOk) {
      return loop_.fail(
          steps,
          fmt::format("settling the last rounds: stacked update failed: {}", to_string(status)),
          options::kExitNumerical);
    }
    for (std::uint64_t s = from; s < to; ++s) tracks_.write(settled_track(s));
    return std::nullopt;
  }

  transport::ProcessCounts counts() const { return {0, rounds_->late_used()}; }

 private:
  // Round `step`'s final estimate, as it leaves the lag.
  wire::TrackEstimate settled_track(std::uint64_t step) const {
    wire::TrackEstimate track = rounds_->track_of(step);
    track.settled(true);
    return track;
  }

  const options::NodeOptions& options_;
  const RunPlan& plan_;
  std::unique_ptr<CenterRounds> rounds_;
  transport::DdsNode node_;
  transport::NodeLoop<wire::Measurement> loop_;
  transport::Writer<wire::TrackEstimate> tracks_;
};

}  // namespace skyfuse::center
