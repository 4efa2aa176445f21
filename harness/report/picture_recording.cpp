#include "report/picture_recording.hpp"

namespace skyfuse::harness {

PictureRecording::PictureRecording(const std::filesystem::path& path, const PicturePlan& plan,
                                   std::uint64_t epoch_ns)
    : channels_(plan, epoch_ns), writer_(path) {
  std::map<std::string, std::uint16_t> schema_ids;  // one schema record per name
  for (const ChannelSpec& spec : channels_.specs()) {
    auto [it, added] = schema_ids.try_emplace(spec.schema_name, 0);
    if (added) it->second = writer_.add_schema(spec.schema_name, "jsonschema", spec.schema);
    channel_ids_.push_back(writer_.add_channel(it->second, spec.topic, "json"));
  }
}

void PictureRecording::add(const PictureFrame& frame) {
  for (const ChannelMessage& m : channels_.frame_messages(frame)) {
    writer_.write(channel_ids_[m.channel], m.log_time_ns, m.json);
  }
}

void PictureRecording::finish(std::string summary_json, int steps) {
  const ChannelMessage m = channels_.summary_message(std::move(summary_json), steps);
  writer_.write(channel_ids_[m.channel], m.log_time_ns, m.json);
  writer_.close();
}

}  // namespace skyfuse::harness
