#pragma once
// A station's picture for the run's filter part and motion model, behind an interface, so that
// the station process of a run with many aircraft (picture_station_node.hpp) and its exchanges
// are compiled once, and only what knows the configuration's track type is compiled by shard of
// the configuration groups (station_picture_shard.cpp; the picture's arithmetic itself is
// core's, picture/pictures_shard.cpp). The center's is fusion_center/center_picture.hpp.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>

#include "skyfuse/asterix/track_numbers.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/transport/picture_round_scans.hpp"
#include "skyfuse/transport/picture_track_writer.hpp"
#include "skyfuse/validation/drop_kind.hpp"
#include "skyfuse/wire/skyfuse_picture.h"

namespace skyfuse::station {

class StationPicture {
 public:
  virtual ~StationPicture() = default;

  /// The run's stations, as the exchanges screen their samples.
  virtual transport::RoundStations round_stations() const = 0;
  /// The noise of the run's station `i` (the plan's order): what its scans carry.
  virtual const DetectionNoise& noise(std::size_t i) const = 0;
  /// The picture's digest (picture/picture_digest.hpp).
  virtual std::uint64_t digest() const = 0;

  /// Predicts the picture to the next round.
  virtual void predict() = 0;
  /// The sample of round `step` of the run's station `i` (this one): `scan` assigned to the
  /// predicted picture, whose digest is `digest`.
  virtual wire::PictureScan sample(std::size_t i, const Scan& scan, std::uint64_t run_id,
                                   std::uint32_t step, std::uint64_t digest) = 0;
  /// Fuses round k: the report of every station whose sample `scans` holds, rebuilt against the
  /// predicted picture (digest `predicted`, picture_round_reports.hpp), or no report at all
  /// where `nothing`. A sample refused is said to `on_refused`. Returns how many were fused.
  virtual std::size_t fuse(std::uint64_t k, const transport::PictureRoundScans& scans,
                           std::uint64_t predicted, bool nothing,
                           const std::function<void(int, DropKind)>& on_refused) = 0;
  /// Numbers the picture's tracks after round k, as every peer does.
  virtual void number(asterix::TrackNumbers& numbers, std::uint64_t k) = 0;

  /// The whole picture, for a peer that parted (wire::PictureState, without its numbers).
  virtual wire::PictureState state(std::uint64_t run_id, std::uint32_t step,
                                   int station_id) const = 0;
  /// The picture after round `step`, for the harness (its tracks not yet numbered).
  virtual wire::PictureRound round(std::uint64_t run_id, std::uint32_t step, int station_id,
                                   std::uint32_t scans_fused) const = 0;
  /// The picture's tracks after round `step` on `skyfuse_track`.
  virtual void publish(transport::PictureTrackWriter& tracks, const asterix::TrackNumbers& numbers,
                       std::uint64_t run_id, std::uint32_t step, int station_id) const = 0;

  /// Keeps a peer's whole picture (its tracks and, where the tracker registers, every station's
  /// registration) as the latest one, in place of the one kept before; false, keeping nothing
  /// new, where it is wrong.
  virtual bool keep_peer_picture(const wire::PictureState& sample) = 0;
  enum class Taken { kTaken, kNoRegistration, kOtherDigest };
  /// Makes the peer's picture kept last this one's, predicted to the next round where
  /// `predict`, if its digest is then `digest`: kTaken. Nothing changes otherwise: its
  /// registration is not of this run's stations, or its digest is another.
  virtual Taken take_peer_picture(bool predict, std::uint64_t digest) = 0;
};

/// The picture of the station of `plan`, whose filter part and motion model lie in shard
/// `Shard`.
template <std::size_t Shard>
std::unique_ptr<StationPicture> make_station_picture_in_shard(const PicturePlan& plan);

/// The picture of a station of `plan`; throws std::logic_error where no picture runs its filter
/// part on its motion model (the scenario's loader refuses those first).
std::unique_ptr<StationPicture> make_station_picture(const PicturePlan& plan);

}  // namespace skyfuse::station
