#include "report/run_recording.hpp"

#include <fmt/format.h>

#include <map>
#include <stdexcept>

#include "report/run_channels.hpp"
#include "skyfuse/record/mcap_summary.hpp"
#include "skyfuse/record/mcap_writer.hpp"

namespace skyfuse::harness {

void write_recording(const RunRecorder& recorder, std::string summary_json,
                     const std::filesystem::path& path, std::uint64_t epoch_ns) {
  RunChannels channels(recorder, epoch_ns);
  record::McapWriter writer(path);
  std::map<std::string, std::uint16_t> schema_ids;  // one schema record per name
  std::vector<std::uint16_t> channel_ids;
  for (const ChannelSpec& spec : channels.specs()) {
    auto [it, added] = schema_ids.try_emplace(spec.schema_name, 0);
    if (added) it->second = writer.add_schema(spec.schema_name, "jsonschema", spec.schema);
    channel_ids.push_back(writer.add_channel(it->second, spec.topic, "json"));
  }
  const auto write = [&](const ChannelMessage& m) {
    writer.write(channel_ids[m.channel], m.log_time_ns, m.json);
  };
  for (const RoundRecord& round : recorder.rounds()) {
    for (const ChannelMessage& m : channels.round_messages(round)) write(m);
  }
  write(channels.summary_message(std::move(summary_json)));
  writer.close();
}

void check_viewable_recording(const std::filesystem::path& path) {
  // The page steps through a recording by its rounds; without them it has nothing to draw.
  constexpr std::string_view kRounds = "/skyfuse/round";
  const auto refuse = [&](const std::string& why) {
    throw std::invalid_argument(fmt::format("{}: {}", path.string(), why));
  };
  record::McapSummary summary;
  try {
    summary = record::read_mcap_summary(path);
  } catch (const record::McapFormatError& e) {
    refuse(e.what());
  }
  const auto rounds = summary.messages_by_topic.find(std::string(kRounds));
  if (rounds == summary.messages_by_topic.end()) {
    refuse(fmt::format(
        "an MCAP file, but not a skyfuse recording: it has no {} channel (skyfuse run --record "
        "writes one)",
        kRounds));
  }
  if (summary.has_statistics && rounds->second == 0) {
    refuse(fmt::format("a skyfuse recording without a single round ({} is empty)", kRounds));
  }
}

}  // namespace skyfuse::harness
