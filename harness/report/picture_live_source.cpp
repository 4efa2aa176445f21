#include "report/picture_live_source.hpp"

#include <algorithm>

#include "run/picture_frame.hpp"

namespace skyfuse::harness {

std::vector<ChannelMessage> PictureLiveSource::batch(std::deque<PictureFrame>& rounds,
                                                     LiveWake& wake) {
  std::vector<ChannelMessage> out;
  for (std::size_t i = 0; i < rounds.size(); ++i) {
    PictureFrame& frame = rounds[i];
    const LiveWake::Send send = wake.send(i, rounds.size(), frame.step + 1 == plan_.scenario.steps);
    if (!send.figures) {
      add_scene(plan_, truth_, frame, false);  // the aircraft, for the entities they leave
      channels_.follow(frame);
      continue;
    }
    add_scene(plan_, truth_, frame);
    for (ChannelMessage& m : channels_.frame_messages(frame, send.scene)) {
      out.push_back(std::move(m));
    }
  }
  return out;
}

}  // namespace skyfuse::harness
