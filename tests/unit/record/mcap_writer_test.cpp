// The MCAP writer against the spec (mcap.dev/spec), read back byte by byte: magic at both ends,
// every offset the summary gives leads to the record it names, the CRCs hold, and the messages
// come back from the chunks through the index. (tests/view/ reads the same files with the
// format's own JavaScript reader.)
#include "skyfuse/record/mcap_writer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "skyfuse/record/crc32.hpp"

namespace skyfuse::record {
namespace {

constexpr std::string_view kMagic{"\x89MCAP0\r\n", 8};

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A cursor over the file's bytes, little-endian as the spec says.
struct Bytes {
  const std::string& data;
  std::size_t at = 0;
  template <typename T>
  T get() {
    T v = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      v = static_cast<T>(
          v | static_cast<T>(static_cast<std::uint64_t>(static_cast<unsigned char>(data.at(at + i)))
                             << (8 * i)));
    }
    at += sizeof(T);
    return v;
  }
  std::string text() {
    const auto n = get<std::uint32_t>();
    std::string s = data.substr(at, n);
    at += n;
    return s;
  }
};

struct Record {
  std::uint8_t op = 0;
  std::string content;
};

Record record_at(const std::string& file, std::size_t offset) {
  Bytes b{file, offset};
  Record r;
  r.op = b.get<std::uint8_t>();
  const auto length = b.get<std::uint64_t>();
  r.content = file.substr(b.at, length);
  return r;
}

std::filesystem::path temp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         (name + "-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + ".mcap");
}

TEST(Crc32, MatchesTheCheckValueAndContinues) {
  EXPECT_EQ(crc32("123456789"), 0xCBF43926u);
  EXPECT_EQ(crc32("6789", crc32("12345")), 0xCBF43926u);
  EXPECT_EQ(crc32(""), 0u);
}

TEST(McapWriter, EveryOffsetOfTheSummaryLeadsToTheRecordItNames) {
  const auto path = temp_file("index");
  {
    McapWriter::Options options;
    options.chunk_bytes = 200;  // several chunks
    McapWriter w(path, options);
    const auto schema = w.add_schema("foxglove.Log", "jsonschema", R"({"type":"object"})");
    const auto a = w.add_channel(schema, "/a", "json", {{"unit", "m"}});
    const auto b = w.add_channel(schema, "/b", "json");
    for (std::uint64_t t = 0; t < 20; ++t) {
      w.write(a, 1000 + t, "{\"a\":" + std::to_string(t) + "}");
      if (t % 2 == 0) w.write(b, 1000 + t, "{\"b\":" + std::to_string(t) + "}");
    }
    EXPECT_EQ(w.message_count(), 30u);
    w.close();
  }
  const std::string file = read_all(path);
  std::filesystem::remove(path);
  ASSERT_GT(file.size(), 2 * kMagic.size());
  EXPECT_EQ(file.substr(0, 8), kMagic);
  EXPECT_EQ(file.substr(file.size() - 8), kMagic);
  EXPECT_EQ(record_at(file, 8).op, 0x01) << "the Header first";

  // Footer: the last record before the magic, 20 bytes of content.
  const std::size_t footer_at = file.size() - 8 - 9 - 20;
  const Record footer = record_at(file, footer_at);
  ASSERT_EQ(footer.op, 0x02);
  Bytes f{footer.content};
  const auto summary_start = f.get<std::uint64_t>();
  const auto summary_offset_start = f.get<std::uint64_t>();
  const auto summary_crc = f.get<std::uint32_t>();
  EXPECT_EQ(summary_crc, crc32(std::string_view(file).substr(summary_start,
                                                             footer_at + 9 + 16 - summary_start)));

  // The Data End record sits right before the summary, with the CRC of everything before it.
  std::size_t data_end_at = 0;
  for (std::size_t at = 8; at < summary_start;) {
    const Record r = record_at(file, at);
    if (r.op == 0x0F) data_end_at = at;
    at += 9 + r.content.size();
  }
  ASSERT_NE(data_end_at, 0u);
  EXPECT_EQ(data_end_at + 9 + 4, summary_start);
  EXPECT_EQ(Bytes{record_at(file, data_end_at).content}.get<std::uint32_t>(),
            crc32(std::string_view(file).substr(0, data_end_at)));

  // Summary offsets: one per group, each group's records all of its opcode.
  std::map<std::uint8_t, std::pair<std::uint64_t, std::uint64_t>> groups;
  for (std::size_t at = summary_offset_start; at < footer_at;) {
    const Record r = record_at(file, at);
    ASSERT_EQ(r.op, 0x0E);
    Bytes o{r.content};
    const auto op = o.get<std::uint8_t>();
    const auto start = o.get<std::uint64_t>();
    const auto length = o.get<std::uint64_t>();
    groups[op] = {start, length};
    for (std::size_t g = start; g < start + length;) {
      const Record member = record_at(file, g);
      EXPECT_EQ(member.op, op);
      g += 9 + member.content.size();
    }
    at += 9 + r.content.size();
  }
  ASSERT_EQ(groups.size(), 4u) << "schemas, channels, statistics, chunk indexes";

  // Statistics.
  Bytes s{record_at(file, groups.at(0x0B).first).content};
  EXPECT_EQ(s.get<std::uint64_t>(), 30u);  // messages
  EXPECT_EQ(s.get<std::uint16_t>(), 1u);   // schemas
  EXPECT_EQ(s.get<std::uint32_t>(), 2u);   // channels
  s.get<std::uint32_t>();                  // attachments
  s.get<std::uint32_t>();                  // metadata
  const auto chunk_count = s.get<std::uint32_t>();
  EXPECT_GT(chunk_count, 2u);
  EXPECT_EQ(s.get<std::uint64_t>(), 1000u);
  EXPECT_EQ(s.get<std::uint64_t>(), 1019u);
  EXPECT_EQ(s.get<std::uint32_t>(), 2u * 10u) << "two map entries of 2 + 8 bytes";
  EXPECT_EQ(s.get<std::uint16_t>(), 0u);
  EXPECT_EQ(s.get<std::uint64_t>(), 20u);
  EXPECT_EQ(s.get<std::uint16_t>(), 1u);
  EXPECT_EQ(s.get<std::uint64_t>(), 10u);

  // Every chunk through its index: the chunk's CRC, then every message through the message
  // indexes, in order, with its sequence number.
  std::map<std::uint16_t, std::vector<std::string>> messages;
  std::uint32_t chunks_seen = 0;
  const auto [indexes_at, indexes_length] = groups.at(0x08);
  for (std::size_t at = indexes_at; at < indexes_at + indexes_length; ++chunks_seen) {
    const Record index = record_at(file, at);
    at += 9 + index.content.size();
    Bytes ci{index.content};
    const auto start = ci.get<std::uint64_t>();
    const auto end = ci.get<std::uint64_t>();
    const auto chunk_at = ci.get<std::uint64_t>();
    const auto chunk_length = ci.get<std::uint64_t>();
    const Record chunk = record_at(file, chunk_at);
    ASSERT_EQ(chunk.op, 0x06);
    EXPECT_EQ(9 + chunk.content.size(), chunk_length);
    Bytes c{chunk.content};
    EXPECT_EQ(c.get<std::uint64_t>(), start);
    EXPECT_EQ(c.get<std::uint64_t>(), end);
    const auto uncompressed = c.get<std::uint64_t>();
    const auto crc = c.get<std::uint32_t>();
    EXPECT_EQ(c.text(), "");
    const auto records_length = c.get<std::uint64_t>();
    EXPECT_EQ(records_length, uncompressed);
    const std::string records = chunk.content.substr(c.at, records_length);
    EXPECT_EQ(crc, crc32(records));

    const auto map_bytes = ci.get<std::uint32_t>();
    for (std::uint32_t read = 0; read < map_bytes; read += 10) {
      const auto channel = ci.get<std::uint16_t>();
      const Record mi = record_at(file, ci.get<std::uint64_t>());
      ASSERT_EQ(mi.op, 0x07);
      Bytes m{mi.content};
      EXPECT_EQ(m.get<std::uint16_t>(), channel);
      const auto pairs = m.get<std::uint32_t>() / 16;
      for (std::uint32_t p = 0; p < pairs; ++p) {
        const auto time = m.get<std::uint64_t>();
        const Record message = record_at(records, m.get<std::uint64_t>());
        ASSERT_EQ(message.op, 0x05);
        Bytes body{message.content};
        EXPECT_EQ(body.get<std::uint16_t>(), channel);
        EXPECT_EQ(body.get<std::uint32_t>(), messages[channel].size()) << "sequence";
        EXPECT_EQ(body.get<std::uint64_t>(), time);
        EXPECT_EQ(body.get<std::uint64_t>(), time) << "publish time = log time";
        EXPECT_GE(time, start);
        EXPECT_LE(time, end);
        messages[channel].push_back(message.content.substr(body.at));
      }
    }
    ci.get<std::uint64_t>();  // message index length
    EXPECT_EQ(ci.text(), "");
  }
  EXPECT_EQ(chunks_seen, chunk_count);
  ASSERT_EQ(messages[0].size(), 20u);
  ASSERT_EQ(messages[1].size(), 10u);
  EXPECT_EQ(messages[0][7], "{\"a\":7}");
  EXPECT_EQ(messages[1][3], "{\"b\":6}");

  // The channel in the summary, metadata included.
  Bytes ch{record_at(file, groups.at(0x04).first).content};
  EXPECT_EQ(ch.get<std::uint16_t>(), 0u);
  EXPECT_EQ(ch.get<std::uint16_t>(), 1u);
  EXPECT_EQ(ch.text(), "/a");
  EXPECT_EQ(ch.text(), "json");
  Bytes meta{ch.text()};
  EXPECT_EQ(meta.text(), "unit");
  EXPECT_EQ(meta.text(), "m");
}

TEST(McapWriter, AnEmptyRecordingIsStillAFile) {
  const auto path = temp_file("empty");
  { McapWriter w(path); }  // closed by the destructor
  const std::string file = read_all(path);
  std::filesystem::remove(path);
  EXPECT_EQ(file.substr(0, 8), kMagic);
  EXPECT_EQ(file.substr(file.size() - 8), kMagic);
  EXPECT_EQ(record_at(file, file.size() - 8 - 29).op, 0x02);
}

TEST(McapWriter, RefusesWhatItCannotWrite) {
  EXPECT_THROW(McapWriter("/nonexistent/dir/x.mcap"), std::runtime_error);
  const auto path = temp_file("refusals");
  McapWriter w(path);
  EXPECT_THROW(w.add_channel(3, "/x", "json"), std::invalid_argument);
  EXPECT_THROW(w.write(0, 1, "{}"), std::invalid_argument);
  w.close();
  EXPECT_THROW(w.write(0, 1, "{}"), std::logic_error);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace skyfuse::record
