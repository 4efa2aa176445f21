#pragma once
// The station process's rounds (station_rounds.hpp), compiled once per fusion
// (station_fusions.hpp) and exchange, in station_rounds_shard.cpp: the sensor and the filter
// part's rule are behind the station's sensing (station_sensing.hpp), compiled apart.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "flat_exchange.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/node_loop.hpp"
#include "skyfuse/transport/node_setup.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "station_fusions.hpp"
#include "station_process.hpp"
#include "station_rounds.hpp"
#include "station_sensing.hpp"
#include "tree_exchange.hpp"

namespace skyfuse::station {
namespace detail {

using transport::RunEnd;

// A station whose rounds `Exchange` carries and `Fusion` fuses: the flat or the tree exchange
// (flat_exchange.hpp, tree_exchange.hpp) of the run's filter part's fusion (station_fusions.hpp),
// with the station's sensing (station_sensing.hpp) behind the fusion's interface. The round
// loop (transport/node_loop.hpp) moves the samples; this is what a station adds to it.
template <typename Fusion, typename Exchange>
class Station {
 public:
  using Sample = typename Exchange::Sample;
  using Sensing = typename Fusion::Sensing;

  // The endpoints are made in a fixed order: the loop's tick and input readers first. `node` is
  // the process's participant: this station's alone, or shared with the process's other
  // stations (station_process.hpp).
  Station(const StationOptions& options, const RunPlan& plan, const StationConfig& me,
          std::unique_ptr<Sensing> sensing, transport::DdsNode& node)
      : options_(options),
        plan_(plan),
        me_(me),
        sensing_(std::move(sensing)),
        node_(node),
        loop_(node_, options.node, me.id, fmt::format("station {}", me.id), Exchange::kInputName,
              plan.scenario.time_step_s, Exchange::input_partitions(plan, me.id)),
        exchange_(node_, loop_.inputs(), plan, me.id, options.node,
                  options.rejoin_step.has_value()),
        measurements_(node_.make_writer<wire::Measurement>()),
        tracks_(node_.make_writer<wire::TrackEstimate>()),
        syncing_(options.rejoin_step.has_value()) {
    if (const auto own = exchange_.own_writer()) loop_.skip_own(me_.id, *own);
  }

  int run() {
    // Matched counts include this participant's own endpoints; the measurement goes to the
    // center and the harness's recorder.
    auto& inputs = loop_.inputs();
    auto& ticks = loop_.ticks();
    if (const RunEnd end = loop_.join(
            [&] {
              return exchange_.matched(inputs) && ticks.matched() >= 1 &&
                     measurements_.matched() >= 2 && tracks_.matched() >= 1;
            },
            [&] {
              return fmt::format(
                  "{}, tick writer {}/1, measurement readers {}/2 (center, harness), track "
                  "readers {}/1 (harness)",
                  exchange_.describe_matched(inputs), ticks.matched(), measurements_.matched(),
                  tracks_.matched());
            })) {
      return *end;
    }
    spdlog::info("joined run {} with {} stations; waiting for ticks", options_.node.run_id,
                 plan_.stations);
    const std::uint64_t first = options_.rejoin_step.value_or(0);
    exchange_.start_at(first);
    return loop_.run(*this, first, static_cast<std::uint64_t>(plan_.scenario.steps), tracks_);
  }

  // What the round loop asks of a station (transport::NodeProcess).

  // Publishes this station's measurement (for the center) and its contribution (for the
  // exchange).
  RunEnd open_round(std::uint64_t k) {
    exchange_.open(k, options_.node.run_id);
    measurements_.write(sensing_->measure(k, options_.node.run_id));
    if (syncing_) return std::nullopt;  // no prior yet: nothing to compute an increment against

    // The round rule screens it as the center does, so both architectures fuse the same
    // measurements; screened out, it still yields a zero increment that tells the peers not to
    // wait for one.
    const OwnContribution result =
        exchange_.contribute(k, *sensing_, options_.node.nis_gate(), options_.node.run_id);
    if (result.refused) {
      loop_.count_drop(*result.refused, "own measurement", me_.id, k);
    } else if (result.status != NumericalStatus::kOk) {
      throw std::runtime_error(
          fmt::format("step {}: increment failed: {}", k, to_string(result.status)));
    }
    return std::nullopt;
  }

  // Checks a sample of the exchange (garbage whoever sent it; then who it claims to be and
  // when; then whether the writer really speaks for that station) and keeps it.
  std::optional<DropKind> receive(const Sample& sample, const transport::WriterId& writer) {
    return exchange_.receive(sample, writer);
  }

  // Everything the round waits for is in.
  bool round_complete() { return exchange_.round_complete(syncing_); }
  // When the exchange's current stage of the round ends (the tree's aggregator has stages).
  std::optional<typename Exchange::SystemTime> wake_at() const { return exchange_.wake_at(); }

  // Fuses what arrived (everything, in a healthy lock-step round) by the round rule and
  // publishes the track, which names exactly the stations fused.
  RunEnd close_round(std::uint64_t k) {
    const RoundFusion fused =
        exchange_.fuse([&](int station_id, DropKind why) { loop_.count_drop(why, station_id, k); });
    auto& fusion = exchange_.fusion();
    if (!fusion.arrived()) {  // only while resynchronising: no peer's prior arrived this round
      spdlog::warn("step {}: no peer increment arrived; still without a prior", k);
      advance();
      return std::nullopt;
    }
    if (fused.status != NumericalStatus::kOk) {
      return loop_.fail(k, fmt::format("step {}: fusion failed: {}", k, to_string(fused.status)),
                        options::kExitNumerical);
    }
    if (fused.resynced) {
      ++resyncs_;
      if (syncing_)
        spdlog::info("step {}: took the peers' prior; contributing from step {}", k, k + 1);
    }
    syncing_ = false;
    tracks_.write(fusion.track(options_.node.run_id, k, me_.id));
    if (const auto settled = fusion.settled_round()) {  // leaves the lag: final now
      tracks_.write(fusion.settled_track(options_.node.run_id, *settled, me_.id));
    }
    fusion.predict();
    advance();
    return std::nullopt;
  }

  // After the last round, with a re-fusion lag: the rounds still in the lag, fused again with
  // what came late, and their final tracks.
  RunEnd settle(std::uint64_t /*steps*/) {
    NumericalStatus status = NumericalStatus::kOk;
    auto& fusion = exchange_.fusion();
    const auto [from, to] = fusion.settle(status);
    if (status != NumericalStatus::kOk) {
      throw std::runtime_error(fmt::format("settling the last rounds: {}", to_string(status)));
    }
    for (std::uint64_t s = from; s < to; ++s) {
      tracks_.write(fusion.settled_track(options_.node.run_id, s, me_.id));
    }
    return std::nullopt;
  }

  // Closes the round in the exchange; a station that took over its cluster has a writer of
  // sums now, whose samples its own reader hears.
  void advance() {
    exchange_.advance();
    if (const auto own = exchange_.own_writer()) loop_.skip_own(me_.id, *own);
  }

  transport::ProcessCounts counts() const { return {resyncs_, exchange_.fusion().late_used()}; }

 private:
  const StationOptions& options_;
  const RunPlan& plan_;
  const StationConfig& me_;
  std::unique_ptr<Sensing> sensing_;
  transport::DdsNode& node_;
  transport::NodeLoop<Sample> loop_;
  Exchange exchange_;
  transport::Writer<wire::Measurement> measurements_;
  transport::Writer<wire::TrackEstimate> tracks_;
  bool syncing_;               // restarted, and no peer's prior taken yet
  std::uint32_t resyncs_ = 0;  // rounds fused onto another station's prior
};

}  // namespace detail

template <typename Fusion>
int run_station_rounds(const StationOptions& options, const RunPlan& plan, const StationConfig& me,
                       std::unique_ptr<AnyStationSensing> any_sensing, transport::DdsNode& node) {
  using detail::Station;
  using Sensing = typename Fusion::Sensing;
  auto* typed = dynamic_cast<Sensing*>(any_sensing.get());
  if (typed == nullptr) {
    throw std::logic_error(fmt::format("station {}: its sensing was not made for filter {} on {}",
                                       me.id, plan.scenario.filter.kind,
                                       plan.scenario.filter.motion_model.kind));
  }
  any_sensing.release();
  std::unique_ptr<Sensing> sensing(typed);
  if (plan.scenario.exchange.kind == ExchangeConfig::Kind::kTree) {
    // load_any_plan refuses the tree for a filter whose fusion cannot sum partial sums yet.
    if constexpr (requires { &Fusion::admit_contribution; }) {
      return transport::make_lifelong<Station<Fusion, TreeExchange<Fusion>>>(
                 options, plan, me, std::move(sensing), node)
          .run();
    } else {
      throw std::logic_error("the tree exchange for a fusion without partial sums");
    }
  }
  return transport::make_lifelong<Station<Fusion, FlatExchange<Fusion>>>(options, plan, me,
                                                                         std::move(sensing), node)
      .run();
}

}  // namespace skyfuse::station
