#pragma once
// `skyfuse run --record FILE.mcap` of a run of many aircraft: every round's messages on the
// channels of picture_channels.hpp, written as the rounds come (a city's picture of a thousand
// aircraft over minutes is not held in memory), then the run's summary.

#include <cstdint>
#include <filesystem>
#include <string>

#include "report/channel_file.hpp"
#include "report/picture_channels.hpp"

namespace skyfuse::harness {

class PictureRecording {
 public:
  /// Creates `path` (std::runtime_error naming it if it cannot); step 0 at `epoch_ns`.
  PictureRecording(const std::filesystem::path& path, const PicturePlan& plan,
                   std::uint64_t epoch_ns);

  void add(const PictureFrame& frame);
  /// summary.json's text after the last of `steps` steps; ends the file.
  void finish(std::string summary_json, int steps);
  std::uint64_t message_count() const { return file_.message_count(); }

 private:
  PictureChannels channels_;
  ChannelFile file_;
};

}  // namespace skyfuse::harness
