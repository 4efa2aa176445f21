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

/// Round k: `rounds` the pictures that came (node order, the center first), `nodes` every node
/// of the run ascending (the center, 0, first), `score` the first station's score of the round.
PictureFrame picture_frame(const PicturePlan& plan, const std::vector<TargetTruth>& truth, int k,
                           const std::vector<wire::PictureRound>& rounds,
                           const std::vector<int>& nodes, const PictureStep& score);

}  // namespace skyfuse::harness
