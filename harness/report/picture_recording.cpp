#include "report/picture_recording.hpp"

namespace skyfuse::harness {

PictureRecording::PictureRecording(const std::filesystem::path& path, const PicturePlan& plan,
                                   std::uint64_t epoch_ns)
    : channels_(plan, epoch_ns), file_(path, channels_.specs()) {}

void PictureRecording::add(const PictureFrame& frame) {
  for (const ChannelMessage& m : channels_.frame_messages(frame)) file_.write(m);
}

void PictureRecording::finish(std::string summary_json, int steps) {
  file_.write(channels_.summary_message(std::move(summary_json), steps));
  file_.close();
}

}  // namespace skyfuse::harness
