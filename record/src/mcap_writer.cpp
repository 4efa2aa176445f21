#include "skyfuse/record/mcap_writer.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "skyfuse/record/crc32.hpp"
#include "skyfuse/record/little_endian.hpp"

namespace skyfuse::record {
namespace {

// Opcodes (mcap.dev/spec, "Records").
enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

constexpr std::string_view kMagic{"\x89MCAP0\r\n", 8};

// Little-endian fixed-width integers, and the spec's length-prefixed String and Bytes.
template <typename T>
void put(std::string& out, T value) {
  append_little_endian(out, value);
}

std::uint32_t length32(std::size_t n) {
  if (n > std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("MCAP: a string, array or map longer than 4 GiB");
  }
  return static_cast<std::uint32_t>(n);
}

void put_string(std::string& out, std::string_view s) {
  put(out, length32(s.size()));
  out.append(s);
}

std::string record(Opcode op, std::string_view content) {
  std::string r;
  r.reserve(9 + content.size());
  put(r, static_cast<std::uint8_t>(op));
  put(r, static_cast<std::uint64_t>(content.size()));
  r.append(content);
  return r;
}

template <typename Value>
std::string map_u16(const std::map<std::uint16_t, Value>& entries) {
  std::string body;
  for (const auto& [key, value] : entries) {
    put(body, key);
    put(body, static_cast<std::uint64_t>(value));
  }
  std::string out;
  put(out, length32(body.size()));
  return out + body;
}

}  // namespace

McapWriter::McapWriter(const std::filesystem::path& path, Options options)
    : out_(path, std::ios::binary | std::ios::trunc), path_(path), options_(std::move(options)) {
  if (!out_) throw std::runtime_error("cannot write " + path.string());
  emit(kMagic);
  std::string header;
  put_string(header, options_.profile);
  put_string(header, options_.library);
  emit(record(kHeader, header));
}

McapWriter::~McapWriter() {
  try {
    close();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor must not throw; close() reports
  }
}

void McapWriter::emit(std::string_view bytes) {
  out_.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  data_crc_ = crc32(bytes, data_crc_);
  offset_ += bytes.size();
}

std::uint16_t McapWriter::add_schema(std::string_view name, std::string_view encoding,
                                     std::string_view data) {
  if (closed_) throw std::logic_error("MCAP: add_schema after close");
  if (schema_records_.size() >= std::numeric_limits<std::uint16_t>::max()) {
    throw std::length_error("MCAP: more than 65535 schemas");
  }
  const auto id = static_cast<std::uint16_t>(schema_records_.size() + 1);  // 0 means "none"
  std::string content;
  put(content, id);
  put_string(content, name);
  put_string(content, encoding);
  put_string(content, data);  // uint32 length-prefixed bytes: the same layout
  emit(record(kSchema, content));
  schema_records_.push_back(std::move(content));
  return id;
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema_id, std::string_view topic,
                                      std::string_view message_encoding,
                                      const std::map<std::string, std::string>& metadata) {
  if (closed_) throw std::logic_error("MCAP: add_channel after close");
  if (schema_id > schema_records_.size()) {
    throw std::invalid_argument("MCAP: channel '" + std::string(topic) + "' names schema " +
                                std::to_string(schema_id) + ", which was never added");
  }
  if (channel_records_.size() > std::numeric_limits<std::uint16_t>::max()) {
    throw std::length_error("MCAP: more than 65536 channels");
  }
  const auto id = static_cast<std::uint16_t>(channel_records_.size());
  std::string content;
  put(content, id);
  put(content, schema_id);
  put_string(content, topic);
  put_string(content, message_encoding);
  std::string entries;
  for (const auto& [key, value] : metadata) {
    put_string(entries, key);
    put_string(entries, value);
  }
  put_string(content, entries);  // Map<string, string>: uint32 byte length, then the entries
  emit(record(kChannel, content));
  channel_records_.push_back(std::move(content));
  sequence_.push_back(0);
  return id;
}

void McapWriter::write(std::uint16_t channel_id, std::uint64_t log_time_ns, std::string_view data) {
  if (closed_) throw std::logic_error("MCAP: write after close");
  if (channel_id >= channel_records_.size()) {
    throw std::invalid_argument("MCAP: message on channel " + std::to_string(channel_id) +
                                ", which was never added");
  }
  std::string content;
  content.reserve(22 + data.size());
  put(content, channel_id);
  put(content, sequence_[channel_id]++);
  put(content, log_time_ns);
  put(content, log_time_ns);  // publish time: the same, as the spec asks when unknown
  content.append(data);

  if (chunk_.empty()) chunk_start_ns_ = chunk_end_ns_ = log_time_ns;
  chunk_start_ns_ = std::min(chunk_start_ns_, log_time_ns);
  chunk_end_ns_ = std::max(chunk_end_ns_, log_time_ns);
  chunk_index_[channel_id].emplace_back(log_time_ns, chunk_.size());
  chunk_ += record(kMessage, content);

  if (message_count_ == 0) start_ns_ = end_ns_ = log_time_ns;
  start_ns_ = std::min(start_ns_, log_time_ns);
  end_ns_ = std::max(end_ns_, log_time_ns);
  ++message_count_;
  ++channel_message_counts_[channel_id];
  if (chunk_.size() >= options_.chunk_bytes) flush_chunk();
}

void McapWriter::flush_chunk() {
  if (chunk_.empty()) return;
  ChunkIndex index;
  index.start_ns = chunk_start_ns_;
  index.end_ns = chunk_end_ns_;
  index.offset = offset_;
  index.records_size = chunk_.size();
  std::string content;
  put(content, chunk_start_ns_);
  put(content, chunk_end_ns_);
  put(content, static_cast<std::uint64_t>(chunk_.size()));
  put(content, crc32(chunk_));
  put_string(content, "");  // no compression
  put(content, static_cast<std::uint64_t>(chunk_.size()));
  content += chunk_;
  const std::string chunk_record = record(kChunk, content);
  index.length = chunk_record.size();
  emit(chunk_record);

  const std::uint64_t indexes_start = offset_;
  for (const auto& [channel, entries] : chunk_index_) {
    std::string body;
    for (const auto& [time, at] : entries) {
      put(body, time);
      put(body, at);
    }
    std::string message_index;
    put(message_index, channel);
    put(message_index, length32(body.size()));
    message_index += body;
    index.message_index_offsets[channel] = offset_;
    emit(record(kMessageIndex, message_index));
  }
  index.message_index_length = offset_ - indexes_start;
  chunks_.push_back(std::move(index));
  chunk_.clear();
  chunk_index_.clear();
}

std::string McapWriter::summary_records(std::uint64_t summary_start, std::string& offsets) const {
  // Grouped by opcode, each group with its Summary Offset record.
  std::string summary;
  const auto group = [&](Opcode op, const std::string& records) {
    if (records.empty()) return;
    std::string offset;
    put(offset, static_cast<std::uint8_t>(op));
    put(offset, summary_start + summary.size());
    put(offset, static_cast<std::uint64_t>(records.size()));
    offsets += record(kSummaryOffset, offset);
    summary += records;
  };
  std::string schemas;
  for (const std::string& s : schema_records_) schemas += record(kSchema, s);
  group(kSchema, schemas);
  std::string channels;
  for (const std::string& c : channel_records_) channels += record(kChannel, c);
  group(kChannel, channels);

  std::string statistics;
  put(statistics, message_count_);
  put(statistics, static_cast<std::uint16_t>(schema_records_.size()));
  put(statistics, static_cast<std::uint32_t>(channel_records_.size()));
  put(statistics, std::uint32_t{0});  // attachments
  put(statistics, std::uint32_t{0});  // metadata
  put(statistics, static_cast<std::uint32_t>(chunks_.size()));
  put(statistics, start_ns_);
  put(statistics, end_ns_);
  statistics += map_u16(channel_message_counts_);
  group(kStatistics, record(kStatistics, statistics));

  std::string chunk_indexes;
  for (const ChunkIndex& c : chunks_) {
    std::string content;
    put(content, c.start_ns);
    put(content, c.end_ns);
    put(content, c.offset);
    put(content, c.length);
    content += map_u16(c.message_index_offsets);
    put(content, c.message_index_length);
    put_string(content, "");
    put(content, c.records_size);  // compressed size: the same, uncompressed
    put(content, c.records_size);
    chunk_indexes += record(kChunkIndex, content);
  }
  group(kChunkIndex, chunk_indexes);
  return summary;
}

void McapWriter::close() {
  if (closed_) return;
  closed_ = true;
  flush_chunk();
  std::string data_end;
  put(data_end, data_crc_);
  emit(record(kDataEnd, data_end));

  const std::uint64_t summary_start = offset_;
  std::string offsets;
  const std::string summary = summary_records(summary_start, offsets);
  const std::uint64_t summary_offset_start = summary_start + summary.size();
  // The footer's CRC covers the summary, the summary offsets and the footer up to its own CRC.
  std::string footer;
  put(footer, static_cast<std::uint8_t>(kFooter));
  put(footer, std::uint64_t{20});
  put(footer, summary.empty() ? 0 : summary_start);
  put(footer, offsets.empty() ? 0 : summary_offset_start);
  put(footer, crc32(footer, crc32(offsets, crc32(summary))));
  emit(summary);
  emit(offsets);
  emit(footer);
  emit(kMagic);
  out_.close();
  if (!out_) throw std::runtime_error("could not finish writing " + path_.string());
}

}  // namespace skyfuse::record
