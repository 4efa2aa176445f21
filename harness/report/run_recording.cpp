#include "report/run_recording.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "report/channel_file.hpp"
#include "report/run_channels.hpp"
#include "skyfuse/record/mcap_summary.hpp"

namespace skyfuse::harness {

void write_recording(const RunRecorder& recorder, std::string summary_json,
                     const std::filesystem::path& path, std::uint64_t epoch_ns) {
  RunChannels channels(recorder, epoch_ns);
  ChannelFile file(path, channels.specs());
  for (const RoundRecord& round : recorder.rounds()) {
    for (const ChannelMessage& m : channels.round_messages(round)) file.write(m);
  }
  file.write(channels.summary_message(std::move(summary_json)));
  file.close();
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
