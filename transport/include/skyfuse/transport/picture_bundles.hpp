#pragma once
/// \file
/// The picture's tree exchange on the wire (wire::PictureBundle, idl/skyfuse_picture.idl): a
/// member's scan on its way to its cluster's aggregator, and the cluster's scans on their way
/// from the aggregator to every station and the center. The aggregator relays each scan as its
/// station sent it and in ascending station id, so what a receiver unpacks is what the flat
/// exchange would have delivered: the same reports, fused by the same arithmetic.
///
/// Screening (both refuse a bundle whole, by its first problem):
///  - a member's scan, at its aggregator (ClusterScans::receive): another run, not a member's
///    scan, another cluster or a station outside it, other than exactly one scan, a scan wrong
///    anywhere or of another step than its bundle's; then who sends it (source_binding.hpp);
///  - a cluster's scans, at a receiver (ClusterBundleScreen::receive): another run, not a
///    cluster's scans, an unknown cluster or a sender that is neither its aggregator (the
///    cluster's lowest id) nor the aggregator's stand-in (the second: kWrongCluster), a writer
///    other than the one the aggregator first spoke with (kDuplicate, unless the cluster was silent
///    the step closed last: a restarted aggregator), a scan of a station outside the cluster
///    (kWrongCluster), a station twice or out of order (kOverlap), a scan of another step; then
///    each scan as PictureScans takes it.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "skyfuse/tracking/cluster_layout.hpp"
#include "skyfuse/tracking/step_collector.hpp"
#include "skyfuse/transport/picture_scans.hpp"
#include "skyfuse/transport/picture_wire.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "skyfuse/transport/tree_partitions.hpp"
#include "skyfuse/validation/drop_kind.hpp"
#include "skyfuse/wire/skyfuse_picture.h"

namespace skyfuse::transport {

/// The partition of the clusters' scans: every station and the center read it. A member's scan
/// travels in its cluster's cluster_up_partition(), which only the aggregator reads.
inline constexpr const char* kPictureClustersPartition = "skyfuse-picture-clusters";

/// Member `scan`'s bundle to the aggregator of `cluster`.
inline wire::PictureBundle member_bundle(const wire::PictureScan& scan, std::size_t cluster) {
  wire::PictureBundle bundle;
  bundle.run_id(scan.run_id());
  bundle.step(scan.step());
  bundle.kind(wire::MEMBER_SCAN);
  bundle.cluster(static_cast<std::uint32_t>(cluster));
  bundle.station_id(scan.station_id());
  bundle.scans().push_back(scan);
  return bundle;
}

/// An aggregator's collection of its cluster's scans, the current step's and the next's: its
/// own (keep()) and its members' (receive()), kept as they were sent.
class ClusterScans {
 public:
  /// The scans of `layout`'s cluster `cluster`, whose stations' sensors are of `kinds`.
  ClusterScans(const ClusterLayout& layout, std::size_t cluster, StationSensorKinds kinds,
               std::uint64_t run_id, std::size_t max_detections)
      : members_(layout.members(cluster).begin(), layout.members(cluster).end()),
        collector_(members_),
        kinds_(std::move(kinds)),
        cluster_(cluster),
        run_id_(run_id),
        max_detections_(max_detections) {}

  /// The aggregator's own scan.
  void keep(const wire::PictureScan& scan) {
    collector_.offer(scan.step(), scan.station_id(), scan);
  }

  /// Keeps a member's scan of the current step or the next, or says why not.
  std::optional<DropKind> receive(const wire::PictureBundle& bundle, const WriterId& writer) {
    if (bundle.run_id() != run_id_) return DropKind::kWrongRun;
    if (bundle.kind() != wire::MEMBER_SCAN || bundle.scans().size() != 1) {
      return DropKind::kOutOfRange;
    }
    const wire::PictureScan& scan = bundle.scans().front();
    if (bundle.cluster() != cluster_ || scan.station_id() != bundle.station_id() ||
        std::find(members_.begin(), members_.end(), scan.station_id()) == members_.end()) {
      return DropKind::kWrongCluster;
    }
    if (scan.run_id() != run_id_) return DropKind::kWrongRun;
    if (scan.step() != bundle.step()) return DropKind::kOutOfRange;
    if (const auto why = picture_scan_from_wire(scan, kinds_, max_detections_).second) return why;
    return admit(collector_, sources_, scan.step(), scan.station_id(), writer, scan);
  }

  /// Every member's scan of the current step is in; every one but `absent`'s.
  bool complete() const { return collector_.complete(); }
  bool complete_but(int absent) const {
    for (std::size_t i = 0; i < members_.size(); ++i) {
      if (members_[i] != absent && !collector_.filled(i)) return false;
    }
    return true;
  }

  /// The cluster's scans of the current step that are in, ascending station id.
  wire::PictureBundle bundle(std::uint32_t step, int aggregator_id) const {
    wire::PictureBundle bundle;
    bundle.run_id(run_id_);
    bundle.step(step);
    bundle.kind(wire::CLUSTER_SCANS);
    bundle.cluster(static_cast<std::uint32_t>(cluster_));
    bundle.station_id(aggregator_id);
    for (std::size_t i = 0; i < members_.size(); ++i) {
      if (collector_.filled(i)) bundle.scans().push_back(collector_.payloads()[i]);
    }
    return bundle;
  }

  void advance() { collector_.advance(); }
  void start_at(std::uint64_t step) { collector_.start_at(step); }

 private:
  std::vector<int> members_;
  StepCollector<wire::PictureScan> collector_;
  SourceBinding sources_;
  StationSensorKinds kinds_;
  std::size_t cluster_;
  std::uint64_t run_id_;
  std::size_t max_detections_;
};

/// A receiver's screen of the clusters' bundles, into its PictureScans.
class ClusterBundleScreen {
 public:
  ClusterBundleScreen(ClusterLayout layout, std::uint64_t run_id)
      : layout_(std::move(layout)), run_id_(run_id) {}

  /// Keeps every scan of a cluster's bundle in `scans`, or none and says why.
  std::optional<DropKind> receive(const wire::PictureBundle& bundle, const WriterId& writer,
                                  PictureScans& scans) {
    if (bundle.run_id() != run_id_) return DropKind::kWrongRun;
    if (bundle.kind() != wire::CLUSTER_SCANS) return DropKind::kOutOfRange;
    const std::size_t cluster = bundle.cluster();
    if (cluster >= layout_.clusters()) return DropKind::kWrongCluster;
    const std::span<const int> members = layout_.members(cluster);
    if (!relays(members, bundle.station_id())) return DropKind::kWrongCluster;
    // Another writer for the aggregator is a restarted one only if its cluster was silent the
    // step closed last.
    if (!aggregators_.would_accept(bundle.station_id(), writer) &&
        !scans.absent_last_step(bundle.station_id())) {
      return DropKind::kDuplicate;
    }
    std::size_t next = 0;  // scans ascend through the members, each at most once
    for (const wire::PictureScan& scan : bundle.scans()) {
      if (scan.step() != bundle.step()) return DropKind::kOutOfRange;
      std::size_t at = 0;
      while (at < members.size() && members[at] != scan.station_id()) ++at;
      if (at == members.size()) return DropKind::kWrongCluster;
      if (at < next) return DropKind::kOverlap;
      next = at + 1;
    }
    if (const auto why = scans.receive_relayed(bundle.scans())) return why;
    aggregators_.bind(bundle.station_id(), writer);
    return std::nullopt;
  }

 private:
  // The cluster's aggregator, or its stand-in (the second id) while the aggregator is silent.
  static bool relays(std::span<const int> members, int id) {
    return id == members.front() || (members.size() >= 2 && id == members[1]);
  }

  ClusterLayout layout_;
  std::uint64_t run_id_;
  SourceBinding aggregators_;  // an aggregator speaks through the writer it first spoke with
};

}  // namespace skyfuse::transport
