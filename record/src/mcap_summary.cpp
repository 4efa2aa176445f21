#include "skyfuse/record/mcap_summary.hpp"

#include <cstring>
#include <fstream>
#include <string_view>
#include <utility>

namespace skyfuse::record {
namespace {

constexpr std::string_view kMagic{"\x89MCAP0\r\n", 8};
constexpr std::uint8_t kFooter = 0x02;
constexpr std::uint8_t kChannel = 0x04;
constexpr std::uint8_t kStatistics = 0x0B;
// Opcode, content length, summary start, summary offset start, CRC.
constexpr std::size_t kFooterRecordBytes = 1 + 8 + 8 + 8 + 4;

// Little-endian fields off the front of a byte range it does not own; any read past its end is
// a format error naming `what` was being read.
class Cursor {
 public:
  Cursor(std::string_view bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}

  template <typename T>
  T number() {
    const std::string_view raw = take(sizeof(T));
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      value |= static_cast<std::uint64_t>(static_cast<unsigned char>(raw[i])) << (8 * i);
    }
    return static_cast<T>(value);
  }
  std::string_view string() { return take(number<std::uint32_t>()); }
  std::string_view take(std::size_t n) {
    if (n > bytes_.size()) {
      throw McapFormatError(what_ + " runs past the end of its section: the file is damaged");
    }
    const std::string_view out = bytes_.substr(0, n);
    bytes_.remove_prefix(n);
    return out;
  }
  bool empty() const { return bytes_.empty(); }

 private:
  std::string_view bytes_;
  std::string what_;
};

std::string read_range(std::ifstream& in, std::uint64_t offset, std::uint64_t length) {
  std::string out(length, '\0');
  in.seekg(static_cast<std::streamoff>(offset));
  in.read(out.data(), static_cast<std::streamsize>(length));
  if (!in) throw std::runtime_error("cannot read the file");
  return out;
}

}  // namespace

McapSummary read_mcap_summary(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(in.tellg());
  if (size < 2 * kMagic.size() || read_range(in, 0, kMagic.size()) != kMagic) {
    throw McapFormatError("not an MCAP file (it does not begin with the MCAP magic bytes)");
  }
  if (size < 2 * kMagic.size() + kFooterRecordBytes ||
      read_range(in, size - kMagic.size(), kMagic.size()) != kMagic) {
    throw McapFormatError(
        "an MCAP file without its end (no closing magic bytes): the recording was cut short");
  }
  const std::uint64_t footer_at = size - kMagic.size() - kFooterRecordBytes;
  const std::string footer_bytes = read_range(in, footer_at, kFooterRecordBytes);
  Cursor footer(footer_bytes, "the footer");
  if (footer.number<std::uint8_t>() != kFooter || footer.number<std::uint64_t>() != 20) {
    throw McapFormatError("an MCAP file whose footer is damaged");
  }
  const auto summary_start = footer.number<std::uint64_t>();
  if (summary_start == 0) {
    throw McapFormatError("an MCAP file without a summary section (no channel list to show)");
  }
  if (summary_start < kMagic.size() || summary_start > footer_at) {
    throw McapFormatError("an MCAP file whose footer points outside the file");
  }
  // The summary runs to the summary offsets, if any, else to the footer; records of other
  // kinds (schemas, chunk indexes, summary offsets) are stepped over.
  const auto offsets_start = footer.number<std::uint64_t>();
  const std::uint64_t summary_end =
      offsets_start != 0 && offsets_start >= summary_start && offsets_start <= footer_at
          ? offsets_start
          : footer_at;
  const std::string summary = read_range(in, summary_start, summary_end - summary_start);
  Cursor records(summary, "a summary record");
  McapSummary out;
  std::map<std::uint16_t, std::string> topic_by_channel;
  std::map<std::uint16_t, std::uint64_t> count_by_channel;
  while (!records.empty()) {
    const auto opcode = records.number<std::uint8_t>();
    Cursor content(records.take(records.number<std::uint64_t>()), "a summary record");
    if (opcode == kChannel) {
      const auto id = content.number<std::uint16_t>();
      content.number<std::uint16_t>();  // schema id
      topic_by_channel[id] = std::string(content.string());
    } else if (opcode == kStatistics) {
      out.has_statistics = true;
      out.message_count = content.number<std::uint64_t>();
      content.take(2 + 4 + 4 + 4 + 4 + 8 + 8);  // the other counts and the time range
      Cursor counts(content.take(content.number<std::uint32_t>()), "the message counts");
      while (!counts.empty()) {
        const auto id = counts.number<std::uint16_t>();
        count_by_channel[id] = counts.number<std::uint64_t>();
      }
    }
  }
  for (const auto& [id, topic] : topic_by_channel) {
    const auto count = count_by_channel.find(id);
    out.messages_by_topic[topic] = count == count_by_channel.end() ? 0 : count->second;
  }
  return out;
}

}  // namespace skyfuse::record
