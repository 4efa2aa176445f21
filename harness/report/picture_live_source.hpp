#pragma once
// What `skyfuse run --live` streams of a run of many aircraft (live_feed.hpp's Source): each
// round's picture as the recording's messages (picture_channels.hpp), thinned to a display's
// rate. The harness hands over the round without its scene; the feed's thread simulates the
// scans of the rounds it sends, so that the run's rounds do not wait on them.

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "report/live_feed.hpp"
#include "report/picture_channels.hpp"
#include "skyfuse/traffic/target_truth.hpp"

namespace skyfuse::harness {

class PictureLiveSource {
 public:
  using Round = PictureFrame;

  /// `plan` and `truth` outlive the source.
  PictureLiveSource(const PicturePlan& plan, const std::vector<TargetTruth>& truth)
      : plan_(plan), truth_(truth), channels_(plan, 0) {}

  const std::vector<ChannelSpec>& specs() const { return channels_.specs(); }
  void set_epoch_ns(std::uint64_t epoch_ns) { channels_.set_epoch_ns(epoch_ns); }
  std::vector<ChannelMessage> batch(std::deque<PictureFrame>& rounds, LiveWake& wake);
  ChannelMessage summary_message(std::string summary_json) const {
    return channels_.summary_message(std::move(summary_json), plan_.scenario.steps);
  }

 private:
  const PicturePlan& plan_;
  const std::vector<TargetTruth>& truth_;
  PictureChannels channels_;
};

using PictureLiveFeed = LiveFeedOf<PictureLiveSource>;

}  // namespace skyfuse::harness
