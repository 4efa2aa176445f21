#pragma once
// What a reader learns of an MCAP file (mcap.dev/spec, major version 0) from its ends alone:
// the magic at both ends, the footer, and the summary section's channels and statistics. Enough
// to tell a recording a page can show from a file that is not one, without reading its chunks.

#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>

namespace skyfuse::record {

/// A file that is not a readable MCAP recording; the message says what is wrong with it.
class McapFormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct McapSummary {
  /// Every channel of the summary, by topic: its message count (from the Statistics record;
  /// zero when the file has none).
  std::map<std::string, std::uint64_t> messages_by_topic;
  std::uint64_t message_count = 0;
  bool has_statistics = false;
};

/// Reads `path`'s summary; throws McapFormatError naming what is wrong (no MCAP magic at the
/// start or the end — a truncated file —, no summary section, a record running past its
/// section) and std::runtime_error when the file cannot be read.
McapSummary read_mcap_summary(const std::filesystem::path& path);

}  // namespace skyfuse::record
