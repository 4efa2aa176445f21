#pragma once
// What `skyfuse run --live` streams of a run of one aircraft (live_feed.hpp's Source): each
// recorded round as the recording's messages (run_channels.hpp), thinned to a display's rate.

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "report/live_feed.hpp"
#include "report/run_channels.hpp"
#include "run/run_report.hpp"

namespace skyfuse::harness {

class RunLiveSource {
 public:
  using Round = RoundRecord;

  explicit RunLiveSource(const RunRecorder& recorder)
      : channels_(recorder, 0), steps_(recorder.plan().scenario.steps) {}

  const std::vector<ChannelSpec>& specs() const { return channels_.specs(); }
  void set_epoch_ns(std::uint64_t epoch_ns) { channels_.set_epoch_ns(epoch_ns); }
  /// The messages for the rounds taken in one wake-up; the trails follow every round.
  std::vector<ChannelMessage> batch(std::deque<RoundRecord>& rounds, LiveWake& wake);
  ChannelMessage summary_message(std::string summary_json) const {
    return channels_.summary_message(std::move(summary_json));
  }

 private:
  RunChannels channels_;
  int steps_;
};

using LiveFeed = LiveFeedOf<RunLiveSource>;

}  // namespace skyfuse::harness
