#include "report/run_live_source.hpp"

#include <algorithm>

namespace skyfuse::harness {

std::vector<ChannelMessage> RunLiveSource::batch(std::deque<RoundRecord>& rounds, LiveWake& wake) {
  std::vector<ChannelMessage> out;
  for (std::size_t i = 0; i < rounds.size(); ++i) {
    const RoundRecord& round = rounds[i];
    const LiveWake::Send send =
        wake.send(i, rounds.size(), round.step + 1 == static_cast<std::uint64_t>(steps_));
    if (!send.figures) {
      channels_.follow(round);
      continue;
    }
    using Detail = RunChannels::Detail;
    const Detail detail = !send.scene   ? Detail::kFiguresOnly
                          : send.trails ? Detail::kEveryRound
                                        : Detail::kDisplayFrame;
    for (ChannelMessage& m : channels_.round_messages(round, detail)) out.push_back(std::move(m));
  }
  return out;
}

}  // namespace skyfuse::harness
