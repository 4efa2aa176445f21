#pragma once
// A round of a run of many aircraft over DDS as a recording draws it (report/picture_channels.hpp):
// the first station's picture as it came, the aircraft, and every station's scan of the round,
// simulated again from the run's seed (the stations' own bits: sim/picture_detections.hpp).

#include <vector>

#include "report/picture_channels.hpp"
#include "skyfuse/metrics/picture_score.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/traffic/target_truth.hpp"
#include "skyfuse/wire/skyfuse_picture.h"

namespace skyfuse::harness {

/// Round k without its scene: `rounds` the pictures that came (node order, the center first),
/// `nodes` every node of the run ascending (the center, 0, first), `score` the first station's
/// score of the round. Cheap enough for the harness's thread.
PictureFrame picture_frame(int k, const std::vector<wire::PictureRound>& rounds,
                           const std::vector<int>& nodes, const PictureStep& score);

/// Adds the aircraft present and, with `scans`, every station's scan of the round to `frame`:
/// M scans simulated again, for a recording or a live stream's thread.
void add_scene(const PicturePlan& plan, const std::vector<TargetTruth>& truth, PictureFrame& frame,
               bool scans = true);

}  // namespace skyfuse::harness
