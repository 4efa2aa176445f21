#pragma once
// A station's side of the flat exchange (the default): every station publishes its contribution
// to every other one, and each fuses all it received by the round rule: M (M - 1) receptions a
// round. `Fusion` is the run's filter part's (station_fusions.hpp). The tree exchange
// (tree_exchange.hpp) has the same interface.

#include <fmt/format.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/tracking/round_rule.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/source_binding.hpp"

namespace skyfuse::station {

template <typename Fusion>
class FlatExchange {
 public:
  using Sample = wire::InformationIncrement;
  using SystemTime = std::chrono::system_clock::time_point;

  /// Every station's input reader is in the default partition.
  static std::vector<std::string> input_partitions(const RunPlan& /*plan*/, int /*id*/) {
    return {};
  }

  /// What the station's drop counts call a sample.
  static constexpr const char* kInputName = "increment";

  /// `syncing`: the station rejoins and has no prior yet.
  FlatExchange(transport::DdsNode& node, transport::Reader<Sample>& /*inputs*/, const RunPlan& plan,
               int id, const options::NodeOptions& options, bool /*syncing*/)
      : fusion_(plan, options.refusion_lag),
        out_(node.make_writer<Sample>()),
        stations_(plan.stations) {
    sources_.bind(id, out_.id());
  }

  Fusion& fusion() { return fusion_; }
  const Fusion& fusion() const { return fusion_; }
  /// This station's writer, whose samples its own reader hears too.
  std::optional<transport::WriterId> own_writer() const { return out_.id(); }

  /// Every station's writer and reader matched (this one's own included).
  bool matched(const transport::Reader<Sample>& in) const {
    return in.matched() >= stations_ && out_.matched() >= stations_;
  }
  std::string describe_matched(const transport::Reader<Sample>& in) const {
    return fmt::format("increment writers {}/{}, increment readers {}/{}", in.matched(), stations_,
                       out_.matched(), stations_);
  }

  void start_at(std::uint64_t step) { fusion_.start_at(step); }
  void open(std::uint64_t /*k*/, std::uint64_t /*run_id*/) {}

  /// This station's contribution, published to every peer.
  template <typename Sensing, typename Gate>
  OwnContribution contribute(std::uint64_t k, const Sensing& sensing, const Gate& gate,
                             std::uint64_t run_id) {
    return fusion_.contribute(k, sensing, gate, run_id,
                              [&](const auto& sample) { out_.write(sample); });
  }

  std::optional<DropKind> receive(const Sample& sample, const transport::WriterId& writer) {
    return fusion_.admit(sample, writer, sources_);
  }

  /// Every station's contribution is in (all but this one's own while it resynchronises).
  bool round_complete(bool syncing) const {
    return fusion_.arrived_count() == fusion_.station_ids().size() - (syncing ? 1 : 0);
  }
  /// No stages within a round.
  std::optional<SystemTime> wake_at() const { return std::nullopt; }

  template <typename OnRefused>
  RoundFusion fuse(OnRefused on_refused) {
    return fusion_.fuse(on_refused);
  }

  void advance() { fusion_.advance(); }

 private:
  Fusion fusion_;
  transport::Writer<Sample> out_;
  int stations_;
  transport::SourceBinding sources_;
};

}  // namespace skyfuse::station
