#pragma once
/// \file
/// A station's side of the picture's tree exchange (scenario `network: {exchange:
/// tree, fanout: k}`). Stations are cut in ascending id into clusters of k, as the one-target
/// tree cuts them (tracking/cluster_layout.hpp); the lowest id of each cluster aggregates it. A
/// round:
///
///  - a member sends its scan to its aggregator (wire::PictureBundle MEMBER_SCAN, partition
///    cluster-<c>-up);
///  - the aggregator sends its cluster's scans, each as its station sent it, to every station
///    and the center (CLUSTER_SCANS, partition skyfuse-picture-clusters): when all its members'
///    are in, or at half the round's deadline;
///  - every station unpacks every cluster's scans into its round's scans and fuses them as a
///    flat peer does (picture_round_scans.hpp).
///
/// Nothing is summed on the way: the increments are every peer's own arithmetic on the relayed
/// detections (docs/picture.md, "The tree", measured why), so the tree changes how many
/// samples a station receives (the C clusters' instead of M stations') and not one bit of what
/// it fuses; the in-process run needs no tree of its own. A member's scan lost on its way up is
/// missing at every peer alike, and the peers stay together; a cluster's bundle lost on its
/// way to one peer parts that peer as a lost flat scan does, and the same rule brings it back.
/// An aggregator whose bundle its cluster's second id did not hear for kSilentRoundsToStandIn
/// rounds is stood in for by that station, which moves its reader into the cluster's up
/// partition and its writer to the clusters' and relays what its members send, until it hears
/// the aggregator again (a restarted one takes its cluster back). A stand-in that only lost
/// the bundles relays besides the aggregator, which costs receptions, not bits. While both relay, a
/// receiver keeps each scan once (PictureScans::receive_relayed).
///
/// Threading: the node's thread, as every endpoint (dds_node.hpp).

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "skyfuse/core/sorted_ids.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/tracking/cluster_layout.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/picture_bundles.hpp"
#include "skyfuse/transport/picture_round_scans.hpp"
#include "skyfuse/transport/picture_wire.hpp"
#include "skyfuse/transport/topics.hpp"
#include "skyfuse/transport/tree_partitions.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::transport {

/// The clusters of a picture run's tree, as every node derives them from the plan.
inline ClusterLayout picture_tree_layout(const PicturePlan& plan) {
  return ClusterLayout(sorted_ascending(plan.participant_ids()),
                       static_cast<std::size_t>(plan.scenario.exchange.fanout));
}

class PictureTreeExchange : public PictureRoundScans {
  using Base = PictureRoundScans;

 public:
  using Sample = wire::PictureBundle;
  using SystemTime = std::chrono::system_clock::time_point;

  /// Where a station's reader of bundles listens: every cluster's scans; an aggregator also its
  /// members'.
  static std::vector<std::string> input_partitions(const PicturePlan& plan, int id) {
    return input_partitions(picture_tree_layout(plan), id);
  }
  static std::vector<std::string> input_partitions(const ClusterLayout& layout, int id) {
    const std::size_t cluster = layout.cluster_of_id(id);
    if (layout.members(cluster).front() == id) {
      return {kPictureClustersPartition, cluster_up_partition(cluster)};
    }
    return {kPictureClustersPartition};
  }

  /// Rounds an aggregator's bundle is heard from no one before its stand-in relays its cluster.
  static constexpr int kSilentRoundsToStandIn = 2;

  /// Station `id`'s exchange on `node` among `stations` (every participant of the run), cut
  /// into `layout`'s clusters, for run `run_id`; a sample of more than `max_detections` is
  /// refused, and an aggregator sends its cluster's scans `collect_span` after its own at the
  /// latest. `inputs`: the station's reader of bundles (made in input_partitions()), which a
  /// stand-in moves; none: this station stands in for nobody.
  PictureTreeExchange(DdsNode& node, const RoundStations& stations, std::uint64_t run_id,
                      std::size_t max_detections, ClusterLayout layout, int id,
                      std::chrono::microseconds collect_span, Reader<wire::PictureBundle>* inputs)
      : Base(stations, run_id, max_detections),
        layout_(std::move(layout)),
        id_(id),
        cluster_(layout_.cluster_of_id(id)),
        aggregating_(layout_.members(cluster_).front() == id),
        stand_in_(inputs != nullptr && layout_.members(cluster_).size() >= 2 &&
                  layout_.members(cluster_)[1] == id),
        inputs_(inputs),
        collect_span_(collect_span),
        screen_(layout_, run_id),
        cluster_scans_(layout_, cluster_, stations.kinds, run_id, max_detections),
        out_(node.make_writer<wire::PictureBundle>({aggregating_
                                                        ? std::string(kPictureClustersPartition)
                                                        : cluster_up_partition(cluster_)})) {}
  /// Station `id`'s exchange in the run of `plan` and `options`: an aggregator's stage ends at
  /// half the round's deadline.
  static PictureTreeExchange of_station(DdsNode& node, const RoundStations& stations,
                                        const PicturePlan& plan, int id,
                                        const options::NodeOptions& options,
                                        Reader<wire::PictureBundle>& inputs) {
    return PictureTreeExchange(node, stations, options.run_id,
                               plan.scenario.tracker.association.max_detections_per_scan,
                               picture_tree_layout(plan), id,
                               (options.realtime_deadline_ms > 0.0 ? options.realtime_deadline()
                                                                   : options.round_deadline()) /
                                   2,
                               &inputs);
  }

  /// A member: its aggregator's reader of scans, and every aggregator's writer of bundles. An
  /// aggregator: its members' writers and every aggregator's (its own included), and every
  /// station's and the center's reader of bundles.
  bool matched(const Reader<wire::PictureBundle>& in) const {
    const auto clusters = static_cast<int>(layout_.clusters());
    if (!aggregating_) return in.matched() >= clusters && out_.matched() >= 1;
    const auto members = static_cast<int>(layout_.members(cluster_).size());
    return in.matched() >= members - 1 + clusters && out_.matched() >= stations() + 1;
  }
  std::string describe_matched(const Reader<wire::PictureBundle>& in) const {
    const auto clusters = static_cast<int>(layout_.clusters());
    if (!aggregating_) {
      return fmt::format("cluster writers {}/{}, aggregator's reader {}/1", in.matched(), clusters,
                         out_.matched());
    }
    return fmt::format("aggregating cluster {}: writers of scans and clusters {}/{}, readers {}/{}",
                       cluster_, in.matched(),
                       static_cast<int>(layout_.members(cluster_).size()) - 1 + clusters,
                       out_.matched(), stations() + 1);
  }
  /// The writer whose samples this station's own reader hears (an aggregator's bundles): the
  /// loop skips them, since send_cluster() keeps them as they go out.
  WriterId own_writer() const { return out_.id(); }

  /// Sends this station's sample of a round (its scan and its report against the predicted
  /// picture, picture_wire.hpp's to_wire) to its aggregator, or keeps it for its cluster's
  /// bundle.
  void publish(const wire::PictureScan& sample) {
    step_ = sample.step();
    if (relaying()) {
      cluster_scans_.keep(sample);
      collect_by_ = std::chrono::system_clock::now() + collect_span_;
      sent_ = false;
    } else {
      out_.write(member_bundle(sample, cluster_));
    }
  }

  /// Keeps a member's scan (an aggregator) or a cluster's scans, or says why not
  /// (picture_bundles.hpp).
  std::optional<DropKind> receive(const wire::PictureBundle& sample, const WriterId& writer) {
    if (sample.kind() == wire::MEMBER_SCAN && relaying()) {
      return cluster_scans_.receive(sample, writer);
    }
    const auto why = screen_.receive(sample, writer, this->scans());
    if (!why && sample.cluster() == cluster_ && sample.station_id() == aggregator()) {
      heard_aggregator_ = true;
    }
    return why;
  }

  /// An aggregator first sends its cluster's scans: when its members' are in, or at half the
  /// deadline. Then every cluster's scans are in.
  bool round_complete() {
    // A stand-in waits for every member but the silent aggregator.
    const bool all_in =
        standing_in_ ? cluster_scans_.complete_but(aggregator()) : cluster_scans_.complete();
    if (relaying() && !sent_ && (all_in || std::chrono::system_clock::now() >= collect_by_)) {
      send_cluster();
    }
    return this->complete();
  }
  /// When an aggregator that has not sent must look again.
  std::optional<SystemTime> wake_at() const {
    if (relaying() && !sent_) return collect_by_;
    return std::nullopt;
  }

  void advance() {
    Base::advance();
    cluster_scans_.advance();
    if (!stand_in_) return;
    aggregator_silent_ = heard_aggregator_ ? 0 : aggregator_silent_ + 1;
    if (!standing_in_ && aggregator_silent_ >= kSilentRoundsToStandIn) {
      stand_in(true);
    } else if (standing_in_ && heard_aggregator_) {
      stand_in(false);
    }
    heard_aggregator_ = false;
  }
  /// Whether this station relays its cluster now: its aggregator, or standing in for it.
  bool relaying() const { return aggregating_ || standing_in_; }
  void start_at(std::uint64_t step) {
    Base::start_at(step);
    cluster_scans_.start_at(step);
  }

 private:
  int stations() const { return static_cast<int>(this->station_count()); }
  int aggregator() const { return layout_.members(cluster_).front(); }

  // Takes the silent aggregator's place (the cluster's up partition in, the clusters' out), or
  // gives it back.
  void stand_in(bool on) {
    inputs_->set_partitions(
        on ? std::vector<std::string>{kPictureClustersPartition, cluster_up_partition(cluster_)}
           : std::vector<std::string>{kPictureClustersPartition});
    out_.set_partitions(
        {on ? std::string(kPictureClustersPartition) : cluster_up_partition(cluster_)});
    standing_in_ = on;
    spdlog::info("{} station {}'s cluster {}", on ? "standing in for" : "giving back", aggregator(),
                 cluster_);
  }

  void send_cluster() {
    const wire::PictureBundle bundle = cluster_scans_.bundle(step_, id_);
    out_.write(bundle);
    this->scans().receive_relayed(bundle.scans());
    sent_ = true;
  }

  ClusterLayout layout_;
  int id_;
  std::size_t cluster_;
  bool aggregating_;
  bool stand_in_;  // the cluster's second id: it relays the cluster while its aggregator is silent
  Reader<wire::PictureBundle>* inputs_;
  bool standing_in_ = false;
  bool heard_aggregator_ = false;  // its cluster's aggregator's bundle, the round now closing
  int aggregator_silent_ = 0;      // rounds without it
  std::chrono::microseconds collect_span_;
  ClusterBundleScreen screen_;
  ClusterScans cluster_scans_;
  Writer<wire::PictureBundle> out_;  // an aggregator's bundles, or a member's scans
  std::uint32_t step_ = 0;
  SystemTime collect_by_{};
  bool sent_ = true;
};

}  // namespace skyfuse::transport
