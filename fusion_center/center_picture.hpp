#pragma once
// The center's picture for the run's filter part and motion model, behind an interface, so that
// the center process of a run with many aircraft (picture_center_node.hpp) is compiled once and
// only what knows the configuration's track type is compiled by shard of the configuration
// groups (center_picture_shard.cpp; the picture's arithmetic itself is core's,
// picture/pictures_shard.cpp).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "skyfuse/asterix/track_numbers.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/transport/picture_track_writer.hpp"
#include "skyfuse/transport/picture_wire.hpp"
#include "skyfuse/wire/skyfuse_picture.h"

namespace skyfuse::center {

class CenterPicture {
 public:
  virtual ~CenterPicture() = default;

  /// The run's stations' sensor kinds, which their samples are checked against.
  virtual transport::StationSensorKinds sensor_kinds() const = 0;
  /// The noise of the run's station `i` (scenario order): what a scan that did not come carries.
  virtual const DetectionNoise& noise(std::size_t i) const = 0;
  /// Round k: predicts the picture, updates it with every station's scan (scenario order) at
  /// once, numbers its tracks by `numbers` and returns it for the harness, numbered.
  virtual wire::PictureRound update(std::uint64_t k, const std::vector<Scan>& scans,
                                    asterix::TrackNumbers& numbers, std::uint64_t run_id,
                                    std::uint32_t scans_fused) = 0;
  /// The picture's tracks after round `step` on `skyfuse_track`.
  virtual void publish(transport::PictureTrackWriter& tracks, const asterix::TrackNumbers& numbers,
                       std::uint64_t run_id, std::uint32_t step) const = 0;
};

/// The center's picture of `plan`, whose filter part and motion model lie in shard `Shard`.
template <std::size_t Shard>
std::unique_ptr<CenterPicture> make_center_picture_in_shard(const PicturePlan& plan);

/// The center's picture of `plan`; throws std::logic_error where no picture runs its filter part
/// on its motion model (the scenario's loader refuses those first).
std::unique_ptr<CenterPicture> make_center_picture(const PicturePlan& plan);

}  // namespace skyfuse::center
