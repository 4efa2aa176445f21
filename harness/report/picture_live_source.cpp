#include "report/picture_live_source.hpp"

#include <algorithm>

#include "run/picture_frame.hpp"

namespace skyfuse::harness {

std::vector<ChannelMessage> PictureLiveSource::batch(std::deque<PictureFrame>& rounds,
                                                     LiveWake& wake) {
  std::vector<ChannelMessage> out;
  for (std::size_t i = 0; i < rounds.size(); ++i) {
    PictureFrame& frame = rounds[i];
    // The scene goes with the newest round of the wake-up and with the run's last round.
    const bool last = frame.step + 1 == plan_.scenario.steps;
    const bool scene = wake.every_round || last || (wake.scene_due && i + 1 == rounds.size());
    if (!wake.wanted || (!scene && wake.figure_tokens < 1.0)) {
      add_scene(plan_, truth_, frame, false);  // the aircraft, for the entities they leave
      channels_.follow(frame);
      continue;
    }
    wake.figure_tokens = std::max(0.0, wake.figure_tokens - 1.0);
    add_scene(plan_, truth_, frame);
    for (ChannelMessage& m : channels_.frame_messages(frame, scene)) out.push_back(std::move(m));
  }
  return out;
}

}  // namespace skyfuse::harness
