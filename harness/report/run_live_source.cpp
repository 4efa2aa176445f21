#include "report/run_live_source.hpp"

#include <algorithm>

namespace skyfuse::harness {

std::vector<ChannelMessage> RunLiveSource::batch(std::deque<RoundRecord>& rounds, LiveWake& wake) {
  std::vector<ChannelMessage> out;
  for (std::size_t i = 0; i < rounds.size(); ++i) {
    const RoundRecord& round = rounds[i];
    // The scene goes with the newest round of the wake-up, and with the last round of the run:
    // a viewer ends on it.
    const bool last = round.step + 1 == static_cast<std::uint64_t>(steps_);
    const bool scene = wake.every_round || last || (wake.scene_due && i + 1 == rounds.size());
    const bool figures = scene || wake.figure_tokens >= 1.0;
    if (!wake.wanted || !figures) {
      channels_.follow(round);
      continue;
    }
    wake.figure_tokens = std::max(0.0, wake.figure_tokens - 1.0);
    using Detail = RunChannels::Detail;
    const bool trails = wake.every_round || last || wake.trails_due;
    const Detail detail = !scene   ? Detail::kFiguresOnly
                          : trails ? Detail::kEveryRound
                                   : Detail::kDisplayFrame;
    for (ChannelMessage& m : channels_.round_messages(round, detail)) out.push_back(std::move(m));
  }
  return out;
}

}  // namespace skyfuse::harness
