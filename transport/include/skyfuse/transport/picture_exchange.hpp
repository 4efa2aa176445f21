#pragma once
/// \file
/// A station's side of the multi-target picture's exchange over DDS. Each round it publishes
/// its scan with its associations against the common predicted picture (wire::PictureScan,
/// transport/picture_wire.hpp) and collects every station's sample of the round that its
/// reader of the topic hears, its own included: every report a peer fuses is rebuilt from the
/// wire, so every peer fuses the same inputs by the same arithmetic and holds the same
/// picture, bit for bit.
///
/// A sample made against another predicted picture (its digest differs from the receiver's) is
/// assigned again here against the receiver's picture and counted: the count tells that peers
/// have parted, and lowest() which picture the peers come back to (the lowest-id station's).
///
/// Threading: the node's thread, as every endpoint (dds_node.hpp).

#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "skyfuse/multitarget/peer_picture.hpp"
#include "skyfuse/multitarget/scan.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/picture_scans.hpp"
#include "skyfuse/transport/picture_wire.hpp"
#include "skyfuse/transport/topics.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::transport {

template <typename Tracks, typename Sensor>
class PictureExchange {
 public:
  static constexpr int M = Sensor::kMeasDim;
  using Picture = PeerPicture<Tracks, Sensor>;
  using Report = typename Picture::Report;

  /// The exchange of `node` among `stations` (every participant of the run), for run `run_id`;
  /// a sample of more than `max_detections` is refused.
  PictureExchange(DdsNode& node, std::span<const KnownStation<Sensor>> stations,
                  std::uint64_t run_id, std::size_t max_detections)
      : stations_(stations.begin(), stations.end()),
        scans_(ids_of(stations), run_id, max_detections),
        run_id_(run_id),
        out_(node.make_writer<wire::PictureScan>()) {}

  /// Every station's writer and reader matched, this one's own included (`in`: the node's
  /// reader of the topic).
  bool matched(const Reader<wire::PictureScan>& in) const {
    const auto stations = static_cast<int>(stations_.size());
    return in.matched() >= stations && out_.matched() >= stations;
  }
  std::string describe_matched(const Reader<wire::PictureScan>& in) const {
    return fmt::format("picture scan writers {}/{}, readers {}/{}", in.matched(), stations_.size(),
                       out_.matched(), stations_.size());
  }
  /// This station's writer, whose samples its own reader hears too.
  WriterId own_writer() const { return out_.id(); }

  /// Publishes this station's round `step`: `scan`, and `report` of it against the predicted
  /// picture whose digest is `picture_digest`. It is also kept here as it went out, for a
  /// station whose reader skips its own samples (a simulated link must not lose them).
  void publish(std::uint32_t step, const Scan<M>& scan, const Report& report,
               std::uint64_t picture_digest) {
    const wire::PictureScan sample = to_wire<Sensor>(scan, report, run_id_, step, picture_digest);
    out_.write(sample);
    if (keep_own_) scans_.receive(sample, out_.id());
  }
  /// Keeps this station's own samples as publish() sends them instead of from its reader.
  void keep_own() { keep_own_ = true; }

  /// Keeps a sample of the current step or the next, or says why not (picture_scans.hpp).
  std::optional<DropKind> receive(const wire::PictureScan& sample, const WriterId& writer) {
    return scans_.receive(sample, writer);
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
      const ReceivedScan<M>* scan = scans_.scan_of(id);
      if (scan == nullptr) continue;
      const auto station = std::find_if(stations_.begin(), stations_.end(),
                                        [&](const auto& s) { return s.id == id; });
      if (scan->picture_digest != digest) {
        ++other_pictures_;
        reassigned_.station_id = id;
        reassigned_.noise = station->noise;
        reassigned_.detections = scan->detections;
        out.push_back(picture.report(*station, reassigned_, work_));
        continue;
      }
      auto report = picture.report_of(*station, scan->detections, scan->associations,
                                      scan->unassociated, scan->dropped);
      if (report) {
        out.push_back(std::move(*report));
      } else {
        on_refused(id, DropKind::kOutOfRange);
      }
    }
    return out;
  }

  /// The lowest-id station whose sample of the current step arrived, and the digest of the
  /// predicted picture it made it against; nothing if none arrived.
  std::optional<std::pair<int, std::uint64_t>> lowest() const {
    for (const int id : scans_.station_ids()) {
      if (const ReceivedScan<M>* scan = scans_.scan_of(id)) {
        return std::pair(id, scan->picture_digest);
      }
    }
    return std::nullopt;
  }
  /// Whether a sample of the current step was made against a picture other than `digest`'s.
  bool any_other_picture(std::uint64_t digest) const {
    for (const int id : scans_.station_ids()) {
      const ReceivedScan<M>* scan = scans_.scan_of(id);
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

 private:
  static std::vector<int> ids_of(std::span<const KnownStation<Sensor>> stations) {
    std::vector<int> ids;
    for (const auto& s : stations) ids.push_back(s.id);
    return ids;
  }

  std::vector<KnownStation<Sensor>> stations_;
  PictureScans<Sensor> scans_;
  std::uint64_t run_id_;
  Writer<wire::PictureScan> out_;
  std::uint64_t other_pictures_ = 0;
  bool keep_own_ = false;
  Scan<M> reassigned_;  // a parted station's detections, assigned here
  AssignmentWork work_;
};

}  // namespace skyfuse::transport
