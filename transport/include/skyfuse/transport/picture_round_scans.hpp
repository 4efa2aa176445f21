#pragma once
/// \file
/// A peer's scans of the current round, however they came (the flat exchange,
/// picture_exchange.hpp, or the tree's, picture_tree_exchange.hpp), and which picture the peers
/// come back to when they have parted (lowest(): the lowest-id station's). The reports a peer
/// fuses from them are picture_round_reports.hpp's.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "skyfuse/picture/known_station.hpp"
#include "skyfuse/picture/picture_digest.hpp"
#include "skyfuse/transport/picture_scans.hpp"
#include "skyfuse/transport/picture_wire.hpp"

namespace skyfuse::transport {

/// Who takes part in a picture run's rounds, as the exchanges screen their samples: every
/// station's id (the plan's order) and its sensor's kind. Nothing of the track type, so that the
/// exchanges are compiled once, not by configuration (picture_round_reports.hpp is the typed
/// side).
struct RoundStations {
  std::vector<int> ids;
  StationSensorKinds kinds;

  template <int N>
  static RoundStations of(std::span<const KnownStation<N>> stations) {
    RoundStations out{{}, StationSensorKinds(stations)};
    for (const auto& s : stations) out.ids.push_back(s.id);
    return out;
  }
};

class PictureRoundScans {
 public:
  /// The scans of `stations` (every participant of the run) in run `run_id`; a sample of more
  /// than `max_detections` is refused.
  PictureRoundScans(const RoundStations& stations, std::uint64_t run_id, std::size_t max_detections)
      : scans_(stations.ids, stations.kinds, run_id, max_detections) {}

  /// The run's stations.
  std::size_t station_count() const { return scans_.station_ids().size(); }
  /// Every station's sample of the current step is in.
  bool complete() const { return scans_.complete(); }
  /// The stations whose sample of the current step is still missing.
  std::vector<int> missing() const { return scans_.missing(); }
  /// The stations, ascending id.
  std::span<const int> station_ids() const { return scans_.station_ids(); }
  /// Station `station_id`'s scan of the current step, or nullptr if it has not arrived.
  const ReceivedScan* scan_of(int station_id) const { return scans_.scan_of(station_id); }

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

 protected:
  PictureScans& scans() { return scans_; }

 private:
  PictureScans scans_;
  std::uint64_t empty_digest_ = empty_picture_digest();
};

}  // namespace skyfuse::transport
