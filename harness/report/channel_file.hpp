#pragma once
// An MCAP file of a run's channels, for either kind of run (report/run_recording.cpp,
// report/picture_recording.cpp): one schema record per schema name, a channel per spec, and
// each message on its spec's channel.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "report/run_channels.hpp"
#include "skyfuse/record/mcap_writer.hpp"

namespace skyfuse::harness {

class ChannelFile {
 public:
  /// Creates `path` (std::runtime_error naming it if it cannot) with the channels `specs`.
  ChannelFile(const std::filesystem::path& path, const std::vector<ChannelSpec>& specs)
      : writer_(path) {
    std::map<std::string, std::uint16_t> schema_ids;
    for (const ChannelSpec& spec : specs) {
      auto [it, added] = schema_ids.try_emplace(spec.schema_name, 0);
      if (added) it->second = writer_.add_schema(spec.schema_name, "jsonschema", spec.schema);
      channel_ids_.push_back(writer_.add_channel(it->second, spec.topic, "json"));
    }
  }

  void write(const ChannelMessage& m) {
    writer_.write(channel_ids_[m.channel], m.log_time_ns, m.json);
  }
  /// Ends the file: its summary and footer.
  void close() { writer_.close(); }
  std::uint64_t message_count() const { return writer_.message_count(); }

 private:
  record::McapWriter writer_;
  std::vector<std::uint16_t> channel_ids_;
};

}  // namespace skyfuse::harness
