#pragma once
// A writer of MCAP files (mcap.dev/spec, major version 0), the recording format Foxglove and
// Lichtblick open. What it writes is what their indexed readers want: messages in chunks
// (uncompressed: a run's JSON is small next to the time it takes), a Message Index after every
// chunk, and a summary — every Schema and Channel again, one Statistics record with each
// channel's message count, a Chunk Index per chunk — with Summary Offsets and CRCs.
//
// Use: add schemas and channels, then write messages in any order of log time; close() ends the
// file. A writer that is destroyed without close() still finishes the file (a run that fails
// halfway leaves a readable recording of what it had).

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace skyfuse::record {

class McapWriter {
 public:
  struct Options {
    std::string profile;                ///< empty: no well-known profile
    std::string library = "skyfuse";    ///< the Header's free-form writer name
    std::size_t chunk_bytes = 1 << 20;  ///< a chunk is closed once its records reach this size
  };

  /// Creates (or truncates) `path`; throws std::runtime_error naming it when it cannot.
  explicit McapWriter(const std::filesystem::path& path, Options options);
  explicit McapWriter(const std::filesystem::path& path) : McapWriter(path, Options{}) {}
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// A schema for channels to refer to; returns its id (1, 2, ...). `encoding`: "jsonschema"
  /// for JSON messages.
  std::uint16_t add_schema(std::string_view name, std::string_view encoding, std::string_view data);
  /// A channel on `topic` whose messages are `message_encoding` ("json") of schema `schema_id`
  /// (0: none); returns its id (0, 1, ...). Throws std::invalid_argument for an unknown schema.
  std::uint16_t add_channel(std::uint16_t schema_id, std::string_view topic,
                            std::string_view message_encoding,
                            const std::map<std::string, std::string>& metadata = {});
  /// One message on `channel_id` at `log_time_ns` (also its publish time). Throws
  /// std::invalid_argument for an unknown channel, std::logic_error after close().
  void write(std::uint16_t channel_id, std::uint64_t log_time_ns, std::string_view data);

  /// Writes the last chunk, the summary and the footer, and closes the file; throws
  /// std::runtime_error if the file could not be written. Later calls do nothing.
  void close();

  std::uint64_t message_count() const { return message_count_; }

 private:
  struct ChunkIndex {
    std::uint64_t start_ns = 0;
    std::uint64_t end_ns = 0;
    std::uint64_t offset = 0;
    std::uint64_t length = 0;
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    std::uint64_t message_index_length = 0;
    std::uint64_t records_size = 0;
  };

  void emit(std::string_view bytes);  ///< to the file, counting offset and data-section CRC
  void flush_chunk();
  std::string summary_records(std::uint64_t summary_start, std::string& offsets) const;

  std::ofstream out_;
  std::filesystem::path path_;
  Options options_;
  bool closed_ = false;
  std::uint64_t offset_ = 0;
  std::uint32_t data_crc_ = 0;

  std::vector<std::string> schema_records_;   ///< content of each, by id - 1
  std::vector<std::string> channel_records_;  ///< content of each, by id
  std::vector<std::uint32_t> sequence_;       ///< next sequence number, by channel id
  std::map<std::uint16_t, std::uint64_t> channel_message_counts_;
  std::uint64_t message_count_ = 0;
  std::uint64_t start_ns_ = 0;
  std::uint64_t end_ns_ = 0;

  // The open chunk: its records, their time span, and per channel (log time, offset in the
  // records) for the Message Index.
  std::string chunk_;
  std::uint64_t chunk_start_ns_ = 0;
  std::uint64_t chunk_end_ns_ = 0;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::vector<ChunkIndex> chunks_;
};

}  // namespace skyfuse::record
