#pragma once
/// \file
/// A peer's scans of the current round, however they came (the flat exchange,
/// picture_exchange.hpp, or the tree's, picture_tree_exchange.hpp), and the reports it fuses
/// from them: every report a peer fuses is rebuilt from the wire, so every peer fuses the same
/// inputs by the same arithmetic and holds the same picture, bit for bit.
///
/// A sample made against another predicted picture (its digest differs from the receiver's) is
/// assigned again here against the receiver's picture and counted: the count tells that peers
/// have parted, and lowest() which picture the peers come back to (the lowest-id station's).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/picture_digest.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/transport/picture_scans.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::transport {

template <typename Tracks>
class PictureRoundScans {
 public:
  using Picture = PeerPicture<Tracks>;
  using Report = typename Picture::Report;
  using Station = typename Picture::Station;

  /// The scans of `stations` (every participant of the run) in run `run_id`; a sample of more
  /// than `max_detections` is refused.
  PictureRoundScans(std::span<const Station> stations, std::uint64_t run_id,
                    std::size_t max_detections)
      : stations_(stations.begin(), stations.end()),
        scans_(ids_of(stations), StationSensorKinds(stations), run_id, max_detections) {}

  /// The run's stations.
  std::size_t station_count() const { return stations_.size(); }
  /// Station `id` of the run (one of them).
  const Station& station(int id) const {
    return *std::find_if(stations_.begin(), stations_.end(),
                         [&](const Station& s) { return s.id == id; });
  }
  /// Every station's sample of the current step is in.
  bool complete() const { return scans_.complete(); }
  /// The stations whose sample of the current step is still missing.
  std::vector<int> missing() const { return scans_.missing(); }

  /// The current step's reports against `picture` (the predicted picture of this step, whose
  /// digest is `picture_digest`: the caller has it already), ascending station id, one per
  /// station whose sample arrived:
  ///  - made against this same picture (its digest): rebuilt from the station's own
  ///    associations;
  ///  - made against another picture (the station had parted): its detections assigned here to
  ///    this picture by the station's own rule (PeerPicture::report), as every peer holding this
  ///    picture assigns them, so that a parted station's scan still counts; counted in
  ///    other_pictures().
  /// A sample made against this same picture whose association names a track the picture does
  /// not hold was not made by an honest station: it is left out and on_refused(station id,
  /// DropKind::kOutOfRange) called.
  template <typename OnRefused>
  std::vector<Report> reports(const Picture& picture, std::uint64_t picture_digest,
                              OnRefused&& on_refused) {
    std::vector<Report> out;
    const std::uint64_t digest = picture_digest;
    for (const int id : scans_.station_ids()) {  // ascending, as fusing wants them
      const ReceivedScan* scan = scans_.scan_of(id);
      if (scan == nullptr) continue;
      const auto station = std::find_if(stations_.begin(), stations_.end(),
                                        [&](const auto& s) { return s.id == id; });
      if (scan->picture_digest != digest) {
        ++other_pictures_;
        reassigned_.station_id = id;
        reassigned_.noise = station->noise;
        reassigned_.detections = scan->detections;
        reassigned_.addresses = scan->addresses;
        out.push_back(picture.report(*station, reassigned_, work_));
        continue;
      }
      auto report = picture.report_of(*station, scan->detections, scan->addresses,
                                      scan->associations, scan->unassociated, scan->dropped);
      if (report) {
        out.push_back(std::move(*report));
      } else {
        on_refused(id, DropKind::kOutOfRange);
      }
    }
    return out;
  }

  /// The station whose picture the peers come back to, and the digest of the predicted picture
  /// it made its sample of the current step against: the lowest-id station whose sample
  /// arrived, made against a picture with tracks if any was. A restarted station starts with an
  /// empty picture, which must not take the others' tracks from them when it is the lowest; a
  /// picture without tracks is the same at every station (empty_picture_digest), so the rule
  /// reads only the samples and every peer that has them picks the same. Nothing if none arrived.
  std::optional<std::pair<int, std::uint64_t>> lowest() const {
    std::optional<std::pair<int, std::uint64_t>> first;
    for (const int id : scans_.station_ids()) {
      if (const ReceivedScan* scan = scans_.scan_of(id)) {
        if (scan->picture_digest != empty_digest_) return std::pair(id, scan->picture_digest);
        if (!first) first = std::pair(id, scan->picture_digest);
      }
    }
    return first;
  }
  /// Whether a sample of the current step was made against a picture other than `digest`'s.
  bool any_other_picture(std::uint64_t digest) const {
    for (const int id : scans_.station_ids()) {
      const ReceivedScan* scan = scans_.scan_of(id);
      if (scan != nullptr && scan->picture_digest != digest) return true;
    }
    return false;
  }

  /// Closes the current step; the next one's samples already taken stay.
  void advance() { scans_.advance(); }
  /// Makes `step` the current one (a station that rejoins a run starts there).
  void start_at(std::uint64_t step) { scans_.start_at(step); }

  /// Samples made against a predicted picture other than this peer's.
  std::uint64_t other_pictures() const { return other_pictures_; }

 protected:
  PictureScans& scans() { return scans_; }

 private:
  static std::vector<int> ids_of(std::span<const Station> stations) {
    std::vector<int> ids;
    for (const auto& s : stations) ids.push_back(s.id);
    return ids;
  }

  std::vector<Station> stations_;
  PictureScans scans_;
  std::uint64_t empty_digest_ = empty_picture_digest();
  std::uint64_t other_pictures_ = 0;
  Scan reassigned_;  // a parted station's detections, assigned here
  AssociationWork work_;
};

}  // namespace skyfuse::transport
