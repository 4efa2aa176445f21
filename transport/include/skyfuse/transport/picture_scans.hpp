#pragma once
/// \file
/// The stations' PictureScans of the current round as a receiver collects them (a peer's
/// exchange, transport/picture_exchange.hpp, and the center alike). Screening, in order: another
/// run's sample, then a sample wrong anywhere (refused whole by its first problem:
/// picture_scan_from_wire), then who it claims to be and when (the current step or the next),
/// and whether its writer speaks for that station (source_binding.hpp). Scans a tree exchange's
/// aggregator relayed come in a bundle whose writer speaks for the cluster (receive_relayed).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "skyfuse/tracking/step_collector.hpp"
#include "skyfuse/transport/picture_wire.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::transport {

class PictureScans {
 public:
  /// The scans of stations `ids` (ascending), whose sensors are of `kinds`, in run `run_id`; a
  /// sample of more than `max_detections` is refused.
  PictureScans(std::span<const int> ids, StationSensorKinds kinds, std::uint64_t run_id,
               std::size_t max_detections)
      : collector_(ids),
        kinds_(std::move(kinds)),
        run_id_(run_id),
        max_detections_(max_detections) {}

  /// Keeps a sample of the current step or the next, or says why not.
  std::optional<DropKind> receive(const wire::PictureScan& sample, const WriterId& writer) {
    if (sample.run_id() != run_id_) return DropKind::kWrongRun;
    auto [scan, why] = picture_scan_from_wire(sample, kinds_, max_detections_);
    if (!scan) return why;
    return admit(collector_, sources_, scan->step, scan->station_id, writer, *scan);
  }

  /// Keeps the scans a tree exchange's aggregator relayed in one bundle, whose sender and
  /// cluster picture_bundles.hpp checked (its writer speaks for its members): each of this run,
  /// right, of the current step or the next and not yet in, or none is kept and the first
  /// problem is said.
  /// A scan already kept is passed over if the bundle relays it unchanged (an aggregator and
  /// its stand-in both relayed it while handing the cluster over), refused if not.
  std::optional<DropKind> receive_relayed(std::span<const wire::PictureScan> samples) {
    relayed_.clear();
    for (const wire::PictureScan& sample : samples) {
      if (sample.run_id() != run_id_) return DropKind::kWrongRun;
      auto [scan, why] = picture_scan_from_wire(sample, kinds_, max_detections_);
      if (!scan) return why;
      if (const auto late = collector_.check(scan->step, scan->station_id)) {
        if (*late == DropKind::kDuplicate && is_kept(*scan)) continue;
        return late;
      }
      relayed_.push_back(std::move(*scan));
    }
    for (const ReceivedScan& scan : relayed_) {
      collector_.offer(scan.step, scan.station_id, scan);
    }
    return std::nullopt;
  }

  /// Every station's scan of the current step is in.
  bool complete() const { return collector_.count() == collector_.station_ids().size(); }
  /// The stations whose scan of the current step is still missing.
  std::vector<int> missing() const { return collector_.missing(); }
  /// Whether station `station_id` delivered nothing in the step closed last.
  bool absent_last_step(int station_id) const { return collector_.absent_last_step(station_id); }
  /// The stations, ascending id.
  std::span<const int> station_ids() const { return collector_.station_ids(); }
  /// Station `station_id`'s scan of the current step, or nullptr if it has not arrived.
  const ReceivedScan* scan_of(int station_id) const {
    const auto i = index_of(station_id);
    return i && collector_.filled(*i) ? &collector_.payloads()[*i] : nullptr;
  }

  /// Closes the current step; the next one's scans already taken stay.
  void advance() { collector_.advance(); }
  /// Makes `step` the current one (a station that rejoins a run starts there).
  void start_at(std::uint64_t step) { collector_.start_at(step); }

 private:
  // Station `station_id`'s place among the stations (ascending id), if it is one.
  std::optional<std::size_t> index_of(int station_id) const {
    const auto ids = collector_.station_ids();
    const auto it = std::lower_bound(ids.begin(), ids.end(), station_id);
    if (it == ids.end() || *it != station_id) return std::nullopt;
    return static_cast<std::size_t>(it - ids.begin());
  }
  // Whether `scan` is the one kept for its station and step, bit for bit (the collector said
  // its slot is filled).
  bool is_kept(const ReceivedScan& scan) const {
    return collector_.payload_at(scan.step, *index_of(scan.station_id)) == scan;
  }

  StepCollector<ReceivedScan> collector_;
  SourceBinding sources_;
  StationSensorKinds kinds_;
  std::uint64_t run_id_;
  std::size_t max_detections_;
  std::vector<ReceivedScan> relayed_;  // a bundle's scans, checked before any is kept
};

}  // namespace skyfuse::transport
