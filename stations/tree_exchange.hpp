#pragma once
// A station's side of the tree exchange (scenario `network: {exchange: tree, fanout: k}`).
// Stations are cut in ascending id into clusters of k (tracking/cluster_layout.hpp); the lowest
// id of each cluster aggregates it. A round:
//
//  - a member publishes its contribution (its increment and the prior it was computed against)
//    to its aggregator (DDS partition cluster-<c>-up, transport/tree_partitions.hpp);
//  - the aggregator sums its cluster's contributions that arrived, weighted, in ascending id
//    (PartialSum::add), and publishes the cluster's sum to every aggregator (partition
//    aggregators): when all its members' are in, or at half the round's deadline;
//  - every aggregator adds the clusters' sums in cluster order into the round's total, when all
//    are in or at three quarters of the deadline, sends it to its members (cluster-<c>-down)
//    and fuses it onto the total's reference; a member fuses the total it receives.
//
// The stages' deadlines bind only when a sample is late. Measured at M = 64, k = 8, real time
// with a 15 ms deadline: nearly every incomplete round is a member whose total came after its
// deadline (the whole chain late), not a closed stage; thirds (5 / 10 ms) gave 66-96 % of
// rounds complete, half and three quarters 94-99 %.
//
// So a round costs M - C + C (C - 1) + M - C receptions for C clusters instead of M (M - 1).
// Every aggregator adds the same bytes in the same order, and every member fuses the bytes its
// aggregator formed: every peer holds the same bits, and the in-process twin (PeerRound with a
// fanout) sums in this order too. A member whose total did not come fuses its own contribution
// alone, as a flat station that heard nobody does.
//
// Every received sum is checked first (validation/partial_sum_checks.hpp): its kind against the
// receiver's role, its cluster and sender (only a cluster's aggregator sends its sum and its
// total), its contributors (inside the cluster, none twice), its numbers; then its round and its
// writer, as a flat station checks an increment.
//
// `Fusion` is the run's filter part's (SingleModelFusion: a filter with an increment rule).

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/tracking/cluster_layout.hpp"
#include "skyfuse/tracking/round_rule.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/partial_wire.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "skyfuse/transport/tree_partitions.hpp"
#include "skyfuse/validation/partial_sum_checks.hpp"

namespace skyfuse::station {

/// The run's clusters, as every node derives them from the plan.
inline ClusterLayout tree_layout(const RunPlan& plan) {
  return ClusterLayout(sorted_ascending(plan.participant_ids()),
                       plan.scenario.exchange.round_fanout());
}

template <typename Fusion>
class TreeExchange {
 public:
  using Sample = wire::PartialSum;
  using SystemTime = std::chrono::system_clock::time_point;
  static constexpr int kDim = Fusion::kDim;
  using Sum = PartialSum<kDim>;

  /// An aggregator hears its members and the other aggregators; a member, its aggregator.
  static std::vector<std::string> input_partitions(const RunPlan& plan, int id) {
    const ClusterLayout layout = tree_layout(plan);
    const std::size_t c = layout.cluster_of_id(id);
    if (layout.members(c).front() == id) {
      return {transport::cluster_up_partition(c), transport::kAggregatorsPartition};
    }
    return {transport::cluster_down_partition(c)};
  }

  /// What the station's drop counts call a sample.
  static constexpr const char* kInputName = "partial sum";

  /// The aggregator's stages divide the round's deadline (options); `syncing`: the station
  /// rejoins and has no prior yet (a member only).
  TreeExchange(transport::DdsNode& node, const RunPlan& plan, int id,
               const options::NodeOptions& options, bool syncing)
      : fusion_(plan, options.refusion_lag),
        layout_(tree_layout(plan)),
        id_(id),
        cluster_(layout_.cluster_of_id(id)),
        aggregator_id_(layout_.members(cluster_).front()),
        round_span_(options.realtime_deadline_ms > 0.0 ? options.realtime_deadline()
                                                       : options.round_deadline()),
        sums_(cluster_indices(layout_.clusters())),
        totals_(std::vector<int>{aggregator_id_}) {
    if (options.refusion_lag != 0) {
      throw std::invalid_argument("the tree exchange takes no re-fusion lag");
    }
    if (aggregates()) {
      if (syncing) {
        throw std::invalid_argument(fmt::format(
            "--rejoin-at-step: station {} aggregates cluster {} of the tree exchange; an "
            "aggregator cannot rejoin a run yet",
            id, cluster_));
      }
      sums_out_.emplace(node.make_writer<Sample>({transport::kAggregatorsPartition}));
      totals_out_.emplace(node.make_writer<Sample>({transport::cluster_down_partition(cluster_)}));
      sum_sources_.bind(id_, sums_out_->id());
    } else {
      up_.emplace(node.make_writer<Sample>({transport::cluster_up_partition(cluster_)}));
    }
    total_.contributors.reserve(plan.participant_ids().size());
    cluster_sum_.contributors.reserve(layout_.fanout());
  }

  Fusion& fusion() { return fusion_; }
  const Fusion& fusion() const { return fusion_; }
  /// The aggregator's writer of cluster sums, whose samples its own reader hears too.
  std::optional<transport::WriterId> own_writer() const {
    if (sums_out_) return sums_out_->id();
    return std::nullopt;
  }

  /// An aggregator: its members' writers, every aggregator's writer of sums (its own
  /// included) and, for its writers, the same readers. A member: its aggregator's both ways.
  bool matched(const transport::Reader<Sample>& in) const {
    if (!aggregates()) return in.matched() >= 1 && up_->matched() >= 1;
    const auto others = static_cast<int>(members()) - 1;
    const auto aggregators = static_cast<int>(clusters());
    return in.matched() >= others + aggregators && sums_out_->matched() >= aggregators &&
           totals_out_->matched() >= others;
  }
  std::string describe_matched(const transport::Reader<Sample>& in) const {
    if (!aggregates()) {
      return fmt::format("aggregator {}: its totals {}/1, its reader of contributions {}/1",
                         aggregator_id_, in.matched(), up_->matched());
    }
    return fmt::format(
        "aggregating cluster {}: writers of contributions and sums {}/{}, readers of sums "
        "{}/{}, readers of totals {}/{}",
        cluster_, in.matched(), members() - 1 + clusters(), sums_out_->matched(), clusters(),
        totals_out_->matched(), members() - 1);
  }

  void start_at(std::uint64_t step) {
    fusion_.start_at(step);
    sums_.start_at(step);
    totals_.start_at(step);
  }

  /// Round k begins: the aggregator's stages are timed from now.
  void open(std::uint64_t k, std::uint64_t run_id) {
    step_ = k;
    run_id_ = run_id;
    const SystemTime now = std::chrono::system_clock::now();
    collect_by_ = now + round_span_ / 2;
    sums_by_ = now + 3 * (round_span_ / 4);
    stage_ = aggregates() ? Stage::kCollecting : Stage::kDone;
  }

  /// This station's contribution: kept by an aggregator, sent to it by a member.
  template <typename Observation, typename Gate>
  OwnContribution contribute(std::uint64_t k, const Observation& observation, const Gate& gate,
                             std::uint64_t run_id) {
    const OwnContribution result =
        fusion_.contribute(k, observation, gate, run_id, [](const auto& /*flat sample*/) {});
    if (aggregates() || result.status != NumericalStatus::kOk) return result;
    const auto* own = fusion_.kept_contribution(id_);
    if (own == nullptr) throw std::logic_error("tree exchange: own contribution not kept");
    outgoing_.clear();
    outgoing_.sum = own->increment;  // unweighted: its aggregator weighs it
    outgoing_.contributors.push_back(id_);
    outgoing_.reference = own->prior;
    up_->write(to_wire(outgoing_, header(wire::CONTRIBUTION)));
    return result;
  }

  std::optional<DropKind> receive(const Sample& sample, const transport::WriterId& writer) {
    switch (sample.kind()) {
      case wire::CONTRIBUTION:
        return receive_contribution(sample, writer);
      case wire::CLUSTER_SUM:
        return receive_cluster_sum(sample, writer);
      case wire::ROUND_TOTAL:
        return receive_total(sample, writer);
    }
    return DropKind::kOutOfRange;
  }

  /// A member: its total is in. An aggregator: its cluster's sum was published (when its
  /// members' contributions were in, or at half the deadline), then every cluster's sum is in
  /// or three quarters of the deadline passed.
  bool round_complete(bool /*syncing*/) {
    if (!aggregates()) return totals_.count() == 1;
    const SystemTime now = std::chrono::system_clock::now();
    if (stage_ == Stage::kCollecting &&
        (fusion_.arrived_count() == members() || now >= collect_by_)) {
      publish_cluster_sum();
      stage_ = Stage::kSumming;
    }
    if (stage_ == Stage::kSumming && (sums_.count() == clusters() || now >= sums_by_)) {
      stage_ = Stage::kDone;
    }
    return stage_ == Stage::kDone;
  }
  /// When the aggregator's current stage ends at the latest.
  std::optional<SystemTime> wake_at() const {
    switch (stage_) {
      case Stage::kCollecting:
        return collect_by_;
      case Stage::kSumming:
        return sums_by_;
      case Stage::kDone:
        break;
    }
    return std::nullopt;
  }

  /// An aggregator: the clusters' sums in cluster order into the total, sent to its members and
  /// fused. A member: the total it received, or its own contribution alone.
  template <typename OnRefused>
  RoundFusion fuse(OnRefused /*on_refused: every sum was checked on arrival*/) {
    if (aggregates()) {
      if (stage_ == Stage::kCollecting) publish_cluster_sum();  // the round ended early
      total_.clear();
      for (std::size_t c = 0; c < clusters(); ++c) {
        if (sums_.filled(c)) total_.add(sums_.payloads()[c]);
      }
      if (members() > 1) totals_out_->write(to_wire(total_, header(wire::ROUND_TOTAL)));
      stage_ = Stage::kDone;
      return fusion_.fuse_total(total_);
    }
    if (totals_.count() == 1) return fusion_.fuse_total(totals_.payloads().front());
    fusion_.sum_cluster(cluster_, cluster_sum_);  // this member's own contribution, if any
    return fusion_.fuse_total(cluster_sum_);
  }

  void advance() {
    fusion_.advance();
    sums_.advance();
    totals_.advance();
  }

 private:
  enum class Stage { kCollecting, kSumming, kDone };

  static std::vector<int> cluster_indices(std::size_t clusters) {
    std::vector<int> indices(clusters);
    std::iota(indices.begin(), indices.end(), 0);
    return indices;
  }

  bool aggregates() const { return id_ == aggregator_id_; }
  std::size_t members() const { return layout_.members(cluster_).size(); }
  std::size_t clusters() const { return layout_.clusters(); }

  transport::SumHeader header(wire::SumKind kind) const {
    return {run_id_, static_cast<std::uint32_t>(step_), id_, kind,
            static_cast<std::uint32_t>(cluster_)};
  }

  void publish_cluster_sum() {
    fusion_.sum_cluster(cluster_, cluster_sum_);
    sums_out_->write(to_wire(cluster_sum_, header(wire::CLUSTER_SUM)));
    sums_.offer(step_, static_cast<int>(cluster_), cluster_sum_);
  }

  // A member's contribution, at its aggregator: from a member of this cluster, for itself only.
  std::optional<DropKind> receive_contribution(const Sample& sample,
                                               const transport::WriterId& writer) {
    const auto sender = static_cast<int>(sample.station_id());
    if (!aggregates() || sample.cluster() != cluster_ ||
        layout_.cluster_of_id(sender) != cluster_) {
      return DropKind::kWrongCluster;
    }
    const auto sum = transport::partial_sum_from_wire<kDim>(sample);
    if (!sum || sum->contributors.size() != 1) return DropKind::kOutOfRange;
    if (sum->contributors.front() != sender) return DropKind::kWrongCluster;
    return fusion_.admit_contribution(sample.step(), sender, {sum->sum, sum->reference}, writer,
                                      contribution_sources_);
  }

  // Another cluster's sum, at an aggregator: from that cluster's aggregator.
  std::optional<DropKind> receive_cluster_sum(const Sample& sample,
                                              const transport::WriterId& writer) {
    const auto sender = static_cast<int>(sample.station_id());
    const std::size_t c = sample.cluster();
    if (!aggregates() || c >= clusters() || layout_.members(c).front() != sender) {
      return DropKind::kWrongCluster;
    }
    const auto sum = transport::partial_sum_from_wire<kDim>(sample);
    if (!sum) return DropKind::kOutOfRange;
    if (const auto why = check_cluster_sum(*sum, layout_, c)) return why;
    return admit(sums_, sum_sources_, sample.step(), static_cast<int>(c), sender, writer, *sum);
  }

  // The round's total, at a member: from its cluster's aggregator.
  std::optional<DropKind> receive_total(const Sample& sample, const transport::WriterId& writer) {
    const auto sender = static_cast<int>(sample.station_id());
    if (aggregates() || sample.cluster() != cluster_ || sender != aggregator_id_) {
      return DropKind::kWrongCluster;
    }
    const auto total = transport::partial_sum_from_wire<kDim>(sample);
    if (!total) return DropKind::kOutOfRange;
    if (const auto why = check_round_total(*total, fusion_.station_ids())) return why;
    return admit(totals_, total_sources_, sample.step(), aggregator_id_, sender, writer, *total);
  }

  // Its round (the collector's window), then its writer (the sender's first one), then kept.
  static std::optional<DropKind> admit(StepCollector<Sum>& collector,
                                       transport::SourceBinding& sources, std::uint64_t step,
                                       int slot, int sender, const transport::WriterId& writer,
                                       const Sum& sum) {
    if (const auto why = collector.check(step, slot)) return why;
    if (!sources.accept(sender, writer)) return DropKind::kDuplicate;
    return collector.offer(step, slot, sum);
  }

  Fusion fusion_;
  ClusterLayout layout_;
  int id_;
  std::size_t cluster_;
  int aggregator_id_;
  std::chrono::microseconds round_span_;
  std::optional<transport::Writer<Sample>> up_;          // a member's, to its aggregator
  std::optional<transport::Writer<Sample>> sums_out_;    // an aggregator's, to the others
  std::optional<transport::Writer<Sample>> totals_out_;  // an aggregator's, to its members
  StepCollector<Sum> sums_;    // an aggregator's: each cluster's sum, by cluster index
  StepCollector<Sum> totals_;  // a member's: its aggregator's total
  transport::SourceBinding contribution_sources_;
  transport::SourceBinding sum_sources_;
  transport::SourceBinding total_sources_;
  Sum outgoing_;     // a member's contribution as a sum of one
  Sum cluster_sum_;  // this cluster's sum
  Sum total_;        // the round's total
  Stage stage_ = Stage::kDone;
  std::uint64_t step_ = 0;
  std::uint64_t run_id_ = 0;
  SystemTime collect_by_;
  SystemTime sums_by_;
};

}  // namespace skyfuse::station
