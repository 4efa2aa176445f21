#include "run/picture_frame.hpp"

#include <algorithm>

#include "run/lockstep_driver.hpp"
#include "skyfuse/sim/picture_detections.hpp"
#include "skyfuse/sim/picture_truth.hpp"
#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::harness {

void add_scene(const PicturePlan& plan, const std::vector<TargetTruth>& truth, PictureFrame& frame,
               bool scans) {
  aircraft_at_step(plan.scenario, plan.stations, truth, frame.step, frame.aircraft);
  if (scans) {
    frame.scans = scan_positions_at(plan.scenario, truth, plan.stations, plan.mc_run, frame.step);
  }
}

PictureFrame picture_frame(int k, const std::vector<wire::PictureRound>& rounds,
                           const std::vector<int>& nodes, const PictureStep& score) {
  PictureFrame frame;
  frame.step = k;
  frame.score = score;
  const wire::PictureRound* first_peer = nullptr;
  for (const int node : nodes) {
    const auto came = std::find_if(rounds.begin(), rounds.end(), [&](const wire::PictureRound& r) {
      return r.source_id() == node;
    });
    FrameNode& n = frame.nodes.emplace_back();
    n.node = node;
    n.delivered = came != rounds.end();
    if (!n.delivered) continue;
    n.scans_fused = came->scans_fused();
    if (node == kCenterNodeId) continue;
    if (first_peer == nullptr) {
      first_peer = &*came;
    } else if (came->picture_digest() != first_peer->picture_digest()) {
      frame.peers_agree = false;
    }
  }
  if (first_peer == nullptr) return frame;
  frame.digest = first_peer->picture_digest();
  for (const wire::PictureBias& b : first_peer->biases()) {
    if (b.estimate().size() != 4 || b.sigma().size() != 4) continue;
    const auto& e = b.estimate();
    const auto& s = b.sigma();
    frame.biases.push_back({b.station_id(), {e[0], e[1], e[2], e[3]}, {s[0], s[1], s[2], s[3]}});
  }
  for (const wire::PictureTrack& t : first_peer->tracks()) {
    FrameTrack& track = frame.tracks.emplace_back();
    track.id = t.track_id();
    track.number = t.number();
    track.confirmed = t.confirmed();
    const int n = static_cast<int>(t.x().size());
    track.position = Vector3(t.x()[0], t.x()[1], t.x()[2]);
    if (const auto p = transport::unpack_upper<Eigen::Dynamic>(t.covariance(), n)) {
      track.position_covariance = p->topLeftCorner<3, 3>();
    }
  }
  return frame;
}

}  // namespace skyfuse::harness
