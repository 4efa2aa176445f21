#pragma once
/// \file
/// The reports a peer fuses from its round's scans (picture_round_scans.hpp), for its track
/// type: every report is rebuilt from the wire, so every peer fuses the same inputs by the same
/// arithmetic and holds the same picture, bit for bit.
///
/// A sample made against another predicted picture (its digest differs from the receiver's) is
/// assigned again here against the receiver's picture and counted: the count tells that peers
/// have parted.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/transport/picture_round_scans.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::transport {

template <typename Tracks>
class PictureRoundReports {
 public:
  using Picture = PeerPicture<Tracks>;
  using Report = typename Picture::Report;
  using Station = typename Picture::Station;

  /// The reports of `stations` (every participant of the run).
  explicit PictureRoundReports(std::span<const Station> stations)
      : stations_(stations.begin(), stations.end()) {}

  /// The run's stations, as the exchanges screen their samples.
  RoundStations round_stations() const {
    return RoundStations::of(std::span<const Station>(stations_));
  }
  /// Station `id` of the run (one of them).
  const Station& station(int id) const {
    return *std::find_if(stations_.begin(), stations_.end(),
                         [&](const Station& s) { return s.id == id; });
  }

  /// The current step's reports in `scans` against `picture` (the predicted picture of this
  /// step, whose digest is `picture_digest`: the caller has it already), ascending station id,
  /// one per station whose sample arrived:
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
  std::vector<Report> reports(const PictureRoundScans& scans, const Picture& picture,
                              std::uint64_t picture_digest, OnRefused&& on_refused) {
    std::vector<Report> out;
    for (const int id : scans.station_ids()) {  // ascending, as fusing wants them
      const ReceivedScan* scan = scans.scan_of(id);
      if (scan == nullptr) continue;
      const Station& known = station(id);
      if (scan->picture_digest != picture_digest) {
        ++other_pictures_;
        assign_scan(reassigned_, id, known.noise, scan);
        out.push_back(picture.report(known, reassigned_, work_));
        continue;
      }
      auto report = picture.report_of(known, published(*scan), scan->associations,
                                      scan->unassociated, scan->dropped);
      if (report) {
        out.push_back(std::move(*report));
      } else {
        on_refused(id, DropKind::kOutOfRange);
      }
    }
    return out;
  }

  /// Samples made against a predicted picture other than this peer's.
  std::uint64_t other_pictures() const { return other_pictures_; }

 private:
  std::vector<Station> stations_;
  std::uint64_t other_pictures_ = 0;
  Scan reassigned_;  // a parted station's detections, assigned here
  AssociationWork work_;
};

}  // namespace skyfuse::transport
