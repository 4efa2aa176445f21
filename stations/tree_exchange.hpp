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
// rounds complete, half and three quarters 90.8-99.6 % (six runs, docs/performance.md).
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
// `Fusion` is the run's filter part's: SingleModelFusion (a filter with an increment rule),
// whose sums are one sample each; ImmFusion, whose sums are one sample per mode
// (transport/imm_partial_wire.hpp); or NcrkfFusion, whose sums are two, of all increments and
// of the definite ones (transport/tdoa_partial_wire.hpp). Its TreeSum is the sum it adds and
// fuses.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
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
#include "skyfuse/transport/imm_partial_wire.hpp"
#include "skyfuse/transport/partial_wire.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "skyfuse/transport/tdoa_partial_wire.hpp"
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
  using Sum = typename Fusion::TreeSum;

  /// What the station's drop counts call a sample.
  static constexpr const char* kInputName = "partial sum";

  /// Where a station's input reader starts: an aggregator hears its members and the other
  /// aggregators; a member, its aggregator.
  static std::vector<std::string> input_partitions(const RunPlan& plan, int id) {
    const ClusterLayout layout = tree_layout(plan);
    return reader_partitions(layout.cluster_of_id(id),
                             layout.members(layout.cluster_of_id(id)).front() == id);
  }

  /// `inputs`: the station's input reader, made in input_partitions(), which this moves when
  /// the station takes over its cluster or gives it back. The aggregator's stages divide the
  /// round's deadline (options); `syncing`: the station rejoins and has no prior yet.
  TreeExchange(transport::DdsNode& node, transport::Reader<Sample>& inputs, const RunPlan& plan,
               int id, const options::NodeOptions& options, bool syncing)
      : fusion_(plan, options.refusion_lag),
        layout_(tree_layout(plan)),
        id_(id),
        cluster_(layout_.cluster_of_id(id)),
        round_span_(options.realtime_deadline_ms > 0.0 ? options.realtime_deadline()
                                                       : options.round_deadline()),
        silent_rounds_to_fail_over_(silent_rounds_to_fail_over(options, plan.scenario.time_step_s)),
        syncing_at_start_(syncing),
        inputs_(inputs),
        views_(initial_views(layout_)),
        silent_(layout_.clusters(), 0),
        heard_late_(layout_.clusters(), false),
        aggregating_(aggregates()),
        node_(node),
        sums_(cluster_indices(layout_.clusters())),
        totals_(std::vector<int>{0}) {
    if (options.refusion_lag != 0) {
      throw std::invalid_argument("the tree exchange takes no re-fusion lag");
    }
    make_role_endpoints();
    total_.contributors.reserve(plan.participant_ids().size());
    cluster_sum_.sum.contributors.reserve(layout_.fanout());
    cluster_sum_.sender = id_;
  }

  Fusion& fusion() { return fusion_; }
  const Fusion& fusion() const { return fusion_; }
  /// The writer of cluster sums, whose samples this station's own reader hears while it
  /// aggregates.
  std::optional<transport::WriterId> own_writer() const {
    if (sums_out_) return sums_out_->id();
    return std::nullopt;
  }

  /// An aggregator: its members' writers, every aggregator's writer of sums (its own
  /// included) and, for its writers, the same readers. A member: its aggregator's both ways. A
  /// station that rejoins needs one writer only: the cluster it finds may have another
  /// aggregator by now, which moves its endpoints back only once it hears this one.
  bool matched(const transport::Reader<Sample>& in) const {
    if (syncing_at_start_) return in.matched() >= 1;
    if (!aggregating_) return in.matched() >= 1 && up_->matched() >= 1;
    const auto others = static_cast<int>(members()) - 1;
    const auto aggregators = static_cast<int>(clusters());
    return in.matched() >= others + aggregators && sums_out_->matched() >= aggregators &&
           totals_out_->matched() >= others;
  }
  std::string describe_matched(const transport::Reader<Sample>& in) const {
    if (!aggregating_) {
      return fmt::format("aggregator {}: its totals {}/1, its reader of contributions {}/1",
                         views_[cluster_], in.matched(), up_->matched());
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
    stage_ = aggregating_ ? Stage::kCollecting : Stage::kDone;
  }

  /// This station's contribution: kept by an aggregator, sent to it by a member.
  template <typename Sensing, typename Gate>
  OwnContribution contribute(std::uint64_t k, const Sensing& sensing, const Gate& gate,
                             std::uint64_t run_id) {
    const OwnContribution result =
        fusion_.contribute(k, sensing, gate, run_id, [](const auto& /*flat sample*/) {});
    if (aggregating_ || result.status != NumericalStatus::kOk) return result;
    // Unweighted: its aggregator weighs it.
    if (!fusion_.own_sum(id_, outgoing_)) {
      throw std::logic_error("tree exchange: own contribution not kept");
    }
    transport::write_sum(*up_, outgoing_, header(wire::CONTRIBUTION));
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
  bool round_complete(bool syncing) {
    if (!aggregating_) return totals_.count() == 1;
    const SystemTime now = std::chrono::system_clock::now();
    const std::size_t expected = members() - (syncing ? 1 : 0);
    if (stage_ == Stage::kCollecting &&
        (fusion_.arrived_count() >= expected || now >= collect_by_)) {
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
  /// on_refused(station_id, why): a contribution the round's fusion refuses (the NCRKF's
  /// indefinite increments); every sum was checked on arrival.
  template <typename OnRefused>
  RoundFusion fuse(OnRefused on_refused) {
    if (aggregating_) {
      if (stage_ == Stage::kCollecting) publish_cluster_sum();  // the round ended early
      total_.clear();
      for (std::size_t c = 0; c < clusters(); ++c) {
        if (sums_.filled(c)) total_.add(sums_.payloads()[c].sum);
      }
      if (members() > 1) transport::write_sum(*totals_out_, total_, header(wire::ROUND_TOTAL));
      stage_ = Stage::kDone;
      return fusion_.fuse_total(total_, on_refused);
    }
    if (totals_.count() == 1) return fusion_.fuse_total(totals_.payloads().front().sum, on_refused);
    fusion_.sum_cluster(cluster_, cluster_sum_.sum);  // this member's own contribution, if any
    return fusion_.fuse_total(cluster_sum_.sum, on_refused);
  }

  /// Closes the round: who aggregates each cluster from the next round on, as this round
  /// showed, and this station's endpoints moved if it takes over its cluster or gives it back.
  void advance() {
    update_views();
    const bool aggregate = aggregates();
    if (aggregate != aggregating_) take_role(aggregate);
    fusion_.advance();
    sums_.advance();
    totals_.advance();
  }

  /// Who aggregates cluster c, as this station last saw it.
  int aggregator_of(std::size_t c) const { return views_[c]; }

 private:
  enum class Stage { kCollecting, kSumming, kDone };

  // How many rounds in a row without a word from its aggregator (its total, or a cluster's sum,
  // in time or not) make a station take that aggregator for dead. A late sum or total counts as
  // a word: its sender lives, and a member that took its place would only add an aggregator to
  // a busy network.
  // - Lock-step on sound links: one round; a whole round's deadline passed.
  // - Over lossy or delayed links one missing total is most often a lost or late sample: with
  //   one round, a 2 % loss made members take their clusters over and give them back every few
  //   rounds (M = 16, k = 4, 100 rounds of loss: 55 sums refused as wrong_cluster, peers up to
  //   0.36 m apart); three rounds in a row are lost with probability p^3.
  // - Real time: a second. On a busy machine a process may not run for several rounds, and
  //   nothing of it is heard, late or not. With five rounds, M = 64 real-time runs that fell
  //   behind for a moment had members take clusters over and give them back (122-231 moves in
  //   each of six runs), every move cost discovery on every node, and no run caught up again.
  static constexpr int kLossySilentRounds = 3;
  static constexpr double kRealtimeSilenceS = 1.0;
  static int silent_rounds_to_fail_over(const options::NodeOptions& options, double time_step_s) {
    if (options.realtime_deadline_ms > 0.0) {
      return std::max(1, static_cast<int>(std::ceil(kRealtimeSilenceS / time_step_s)));
    }
    if (options.loss.enabled() || options.delay.enabled()) return kLossySilentRounds;
    return 1;
  }
  static constexpr const char* kStandbyPartition = "skyfuse-standby";
  // After a station moves its endpoints, its own cluster's silence does not count for this many
  // rounds, or it could take over and give back in turn while the others match them.
  static constexpr int kSettlingRounds = 3;

  // A sum and the station that sent it: of two for one cluster and round, the lower sender's
  // is kept (the lowest live id aggregates).
  struct SentSum {
    Sum sum;
    int sender = 0;
  };

  static std::vector<std::string> reader_partitions(std::size_t c, bool aggregating) {
    if (aggregating) return {transport::cluster_up_partition(c), transport::kAggregatorsPartition};
    return {transport::cluster_down_partition(c)};
  }
  static std::vector<std::string> sums_partitions(bool aggregating) {
    return {aggregating ? transport::kAggregatorsPartition : kStandbyPartition};
  }
  static std::vector<std::string> totals_partitions(std::size_t c, bool aggregating) {
    return {aggregating ? transport::cluster_down_partition(c) : std::string(kStandbyPartition)};
  }

  static std::vector<int> cluster_indices(std::size_t clusters) {
    std::vector<int> indices(clusters);
    std::iota(indices.begin(), indices.end(), 0);
    return indices;
  }
  static std::vector<int> initial_views(const ClusterLayout& layout) {
    std::vector<int> views;
    for (std::size_t c = 0; c < layout.clusters(); ++c) views.push_back(layout.members(c).front());
    return views;
  }

  bool aggregates() const { return views_[cluster_] == id_; }
  std::size_t members() const { return layout_.members(cluster_).size(); }
  std::size_t clusters() const { return layout_.clusters(); }
  bool in_cluster(std::size_t c, int station) const { return layout_.cluster_of_id(station) == c; }

  transport::SumHeader header(wire::SumKind kind) const {
    return {run_id_, static_cast<std::uint32_t>(step_), id_, kind,
            static_cast<std::uint32_t>(cluster_)};
  }

  void publish_cluster_sum() {
    fusion_.sum_cluster(cluster_, cluster_sum_.sum);
    transport::write_sum(*sums_out_, cluster_sum_.sum, header(wire::CLUSTER_SUM));
    if (const auto why = sums_.check(step_, static_cast<int>(cluster_))) {
      // A lower id's sum for this cluster came first: it aggregates, and is kept.
      if (*why != DropKind::kDuplicate) throw std::logic_error("own cluster sum out of its round");
      return;
    }
    sums_.offer(step_, static_cast<int>(cluster_), cluster_sum_);
  }

  // Each cluster's aggregator from the next round: whoever sent the sum (or this member's total)
  // kept this round; after enough silent rounds, the next member of the cluster.
  void update_views() {
    auto observe = [&](std::size_t c, const StepCollector<SentSum>& kept, std::size_t slot) {
      if (kept.filled(slot)) {
        views_[c] = kept.payloads()[slot].sender;
        silent_[c] = 0;
      } else if (heard_late_[c]) {
        silent_[c] = 0;  // alive, only out of step
      } else if (c == cluster_ && settling_ > 0) {
        // Just moved: the others match its endpoints only as discovery tells them.
      } else if (++silent_[c] >= silent_rounds_to_fail_over_) {
        views_[c] = next_member(c, views_[c]);
        silent_[c] = 0;
      }
    };
    if (!aggregating_) {
      observe(cluster_, totals_, 0);
    } else {
      for (std::size_t c = 0; c < clusters(); ++c) observe(c, sums_, c);
    }
    if (lower_aggregator_ && *lower_aggregator_ < views_[cluster_]) {
      views_[cluster_] = *lower_aggregator_;
      silent_[cluster_] = 0;
    }
    lower_aggregator_.reset();
    std::fill(heard_late_.begin(), heard_late_.end(), false);
    if (settling_ > 0) --settling_;
  }
  int next_member(std::size_t c, int after) const {
    const auto ids = layout_.members(c);
    const auto it = std::upper_bound(ids.begin(), ids.end(), after);
    return it == ids.end() ? ids.front() : *it;
  }

  // The writers this station's role needs and it does not have yet: a member's way up, or an
  // aggregator's ways across and down, made when first needed. Idle writers on every member
  // looked costly: M = 64, lock-step, four alternating pairs, 49-56 rounds/s with a standby
  // sums and totals writer on every member against 57-65 without.
  void make_role_endpoints() {
    if (!aggregating_) {
      if (!up_) up_.emplace(node_.make_writer<Sample>({transport::cluster_up_partition(cluster_)}));
      return;
    }
    if (!sums_out_) {
      sums_out_.emplace(node_.make_writer<Sample>(sums_partitions(true)));
      sum_sources_.bind(id_, sums_out_->id());
    }
    if (!totals_out_)
      totals_out_.emplace(node_.make_writer<Sample>(totals_partitions(cluster_, true)));
  }

  // Moves this station's endpoints into the aggregator's partitions, or back to a member's.
  void take_role(bool aggregate) {
    spdlog::info("step {}: {} cluster {}", step_, aggregate ? "takes over" : "gives back",
                 cluster_);
    inputs_.set_partitions(reader_partitions(cluster_, aggregate));
    if (sums_out_) sums_out_->set_partitions(sums_partitions(aggregate));
    if (totals_out_) totals_out_->set_partitions(totals_partitions(cluster_, aggregate));
    aggregating_ = aggregate;
    make_role_endpoints();
    settling_ = kSettlingRounds;
  }

  // A member's contribution, at its aggregator: from a member of this cluster, for itself only.
  std::optional<DropKind> receive_contribution(const Sample& sample,
                                               const transport::WriterId& writer) {
    const auto sender = static_cast<int>(sample.station_id());
    if (!aggregating_ || sample.cluster() != cluster_ || !in_cluster(cluster_, sender)) {
      return DropKind::kWrongCluster;
    }
    std::optional<DropKind> why;
    const Sum* sum = assembler_.feed(sample, writer, why);
    if (sum == nullptr) return why;  // refused, or an IMM's sum not complete yet
    if (sum->contributors.size() != 1) return DropKind::kOutOfRange;
    if (sum->contributors.front() != sender) return DropKind::kWrongCluster;
    return fusion_.admit_contribution(sample.step(), sender, *sum, writer, contribution_sources_);
  }

  // A cluster's sum, at an aggregator: from a member of that cluster no higher than the one
  // this station takes for its aggregator.
  std::optional<DropKind> receive_cluster_sum(const Sample& sample,
                                              const transport::WriterId& writer) {
    const auto sender = static_cast<int>(sample.station_id());
    const std::size_t c = sample.cluster();
    if (!aggregating_ || c >= clusters() || !in_cluster(c, sender) || sender > views_[c]) {
      return DropKind::kWrongCluster;
    }
    std::optional<DropKind> why;
    const Sum* sum = assembler_.feed(sample, writer, why);
    if (sum == nullptr) return why;
    if (const auto bad = check_cluster_sum(*sum, layout_, c)) return bad;
    // This station's own sums never reach here (the loop skips its writer's): another writer
    // speaks for it. Its round is checked first, as for any sum.
    if (sender == id_)
      return sums_.check(sample.step(), static_cast<int>(c)).value_or(DropKind::kDuplicate);
    const auto kept =
        keep_lowest(sums_, sum_sources_, sample.step(), static_cast<int>(c), sender, writer, *sum);
    if (c == cluster_) note_lower_aggregator(sender, kept);
    note_late(c, sender, writer, sum_sources_, kept);
    return kept;
  }

  // The round's total, at a member: from a member of its cluster no higher than its aggregator.
  std::optional<DropKind> receive_total(const Sample& sample, const transport::WriterId& writer) {
    const auto sender = static_cast<int>(sample.station_id());
    if (aggregating_ || sample.cluster() != cluster_ || !in_cluster(cluster_, sender) ||
        sender > views_[cluster_] || sender == id_) {
      return DropKind::kWrongCluster;
    }
    std::optional<DropKind> why;
    const Sum* total = assembler_.feed(sample, writer, why);
    if (total == nullptr) return why;
    if (const auto bad = check_round_total(*total, fusion_.station_ids())) return bad;
    const auto kept =
        keep_lowest(totals_, total_sources_, sample.step(), 0, sender, writer, *total);
    note_lower_aggregator(sender, kept);
    note_late(cluster_, sender, writer, total_sources_, kept);
    return kept;
  }

  // A sum or total of this station's cluster, kept or too late for its round, from a lower id
  // than the aggregator this station hears from: that station aggregates (restarted, or heard
  // again). Late ones count too: a station that aggregates in its place closes its rounds before
  // the lower one's sum comes, and would otherwise never learn of it.
  void note_lower_aggregator(int sender, std::optional<DropKind> kept) {
    if (sender >= views_[cluster_] || (kept && *kept != DropKind::kStaleStep)) return;
    lower_aggregator_ = std::min(lower_aggregator_.value_or(sender), sender);
  }

  // Who may speak for a sender of sums or totals: its first writer, or a new one once nothing
  // came from the sender in the round closed last (a restarted process; trust on first use, as
  // transport::admit - DDS-Security authenticates). `current`: the receiver's round, not the
  // one the sample claims, which a forger chooses.
  class Senders {
   public:
    void bind(int sender, const transport::WriterId& writer) { binding_.bind(sender, writer); }
    bool would_accept(int sender, const transport::WriterId& writer) const {
      return binding_.would_accept(sender, writer);
    }
    bool accept(int sender, const transport::WriterId& writer, std::uint64_t step,
                std::uint64_t current) {
      if (!binding_.accept(sender, writer)) {
        const auto it = last_step_.find(sender);
        if (it != last_step_.end() && it->second + 1 >= current) return false;
        binding_.bind(sender, writer);
      }
      std::uint64_t& last = last_step_[sender];
      last = std::max(last, step);
      return true;
    }

   private:
    transport::SourceBinding binding_;
    std::map<int, std::uint64_t> last_step_;  // the latest round accepted from each sender
  };

  // A sum or total of cluster c for a round this station is not in (too late, or this station
  // is behind), from the aggregator it hears for c and through a writer that may speak for it:
  // that aggregator lives (update_views()).
  void note_late(std::size_t c, int sender, const transport::WriterId& writer,
                 const Senders& senders, std::optional<DropKind> kept) {
    const bool out_of_round = kept == DropKind::kStaleStep || kept == DropKind::kFutureStep;
    if (out_of_round && sender == views_[c] && senders.would_accept(sender, writer)) {
      heard_late_[c] = true;
    }
  }

  // Its round (the collector's window), then its writer, then kept; if the slot holds a higher
  // sender's, replaced: the lower one aggregates.
  static std::optional<DropKind> keep_lowest(StepCollector<SentSum>& collector, Senders& senders,
                                             std::uint64_t step, int slot, int sender,
                                             const transport::WriterId& writer, const Sum& sum) {
    const auto why = collector.check(step, slot);
    const bool lower = why == DropKind::kDuplicate &&
                       sender < collector.payload_at(step, static_cast<std::size_t>(slot)).sender;
    if (why && !lower) return why;
    if (!senders.accept(sender, writer, step, collector.current_step())) {
      return DropKind::kDuplicate;
    }
    if (lower) {
      collector.replace(step, slot, {sum, sender});
      return std::nullopt;
    }
    return collector.offer(step, slot, {sum, sender});
  }

  Fusion fusion_;
  ClusterLayout layout_;
  int id_;
  std::size_t cluster_;
  std::chrono::microseconds round_span_;
  int silent_rounds_to_fail_over_;
  bool syncing_at_start_;
  transport::Reader<Sample>& inputs_;
  std::vector<int> views_;        // each cluster's aggregator, as this station sees it
  std::vector<int> silent_;       // rounds in a row without its sum (a member: without its total)
  std::vector<bool> heard_late_;  // this round: its sum (or total) came, too late
  std::optional<int> lower_aggregator_;  // heard this round: see note_lower_aggregator()
  int settling_ = 0;                     // rounds left since this station moved its endpoints
  bool aggregating_;  // this station's endpoints are in its cluster's aggregator's places
  transport::DdsNode& node_;
  std::optional<transport::Writer<Sample>> up_;          // to the aggregator: contributions
  std::optional<transport::Writer<Sample>> sums_out_;    // to the others: sums (standby: a member)
  std::optional<transport::Writer<Sample>> totals_out_;  // to the members (standby: a member)
  StepCollector<SentSum> sums_;    // an aggregator's: each cluster's sum, by cluster index
  StepCollector<SentSum> totals_;  // a member's: its aggregator's total
  transport::SourceBinding contribution_sources_;
  Senders sum_sources_;
  Senders total_sources_;
  transport::SumAssembler<Sum> assembler_;  // received samples back into sums
  Sum outgoing_;                            // a member's contribution as a sum of one
  SentSum cluster_sum_;                     // this cluster's sum
  Sum total_;                               // the round's total
  Stage stage_ = Stage::kDone;
  std::uint64_t step_ = 0;
  std::uint64_t run_id_ = 0;
  SystemTime collect_by_;
  SystemTime sums_by_;
};

}  // namespace skyfuse::station
