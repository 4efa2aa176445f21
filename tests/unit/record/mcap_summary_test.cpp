// The summary reader against files the writer made, and against what is not a whole recording:
// a text file, a file cut short, a file without a summary section.
#include "skyfuse/record/mcap_summary.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "skyfuse/record/mcap_writer.hpp"

namespace skyfuse::record {
namespace {

class McapSummaryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("skyfuse_mcap_summary_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Two channels, three messages on the first, none on the second.
  std::filesystem::path written() const {
    const auto path = dir_ / "run.mcap";
    McapWriter writer(path);
    const auto schema = writer.add_schema("skyfuse.Round", "jsonschema", "{}");
    const auto rounds = writer.add_channel(schema, "/skyfuse/round", "json");
    writer.add_channel(schema, "/skyfuse/summary", "json");
    for (std::uint64_t k = 0; k < 3; ++k) writer.write(rounds, 1000 + k, "{}");
    writer.close();
    return path;
  }

  static std::string read_all(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  std::filesystem::path with_content(const std::string& name, const std::string& bytes) const {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  std::filesystem::path dir_;
};

TEST_F(McapSummaryTest, ReadsEveryChannelAndItsMessageCount) {
  const McapSummary summary = read_mcap_summary(written());
  EXPECT_TRUE(summary.has_statistics);
  EXPECT_EQ(summary.message_count, 3u);
  ASSERT_EQ(summary.messages_by_topic.size(), 2u);
  EXPECT_EQ(summary.messages_by_topic.at("/skyfuse/round"), 3u);
  EXPECT_EQ(summary.messages_by_topic.at("/skyfuse/summary"), 0u);
}

TEST_F(McapSummaryTest, RefusesATextFile) {
  const auto path = with_content("garbage.mcap", "a text file, not a recording\n");
  EXPECT_THROW(
      {
        try {
          read_mcap_summary(path);
        } catch (const McapFormatError& e) {
          EXPECT_STREQ(e.what(), "not an MCAP file (it does not begin with the MCAP magic bytes)");
          throw;
        }
      },
      McapFormatError);
}

TEST_F(McapSummaryTest, RefusesAFileCutShort) {
  const std::string whole = read_all(written());
  for (const std::size_t keep : {whole.size() - 1, whole.size() / 2, std::size_t{20}}) {
    const auto path = with_content("cut.mcap", whole.substr(0, keep));
    try {
      read_mcap_summary(path);
      ADD_FAILURE() << "kept " << keep << " of " << whole.size() << " bytes: read";
    } catch (const McapFormatError& e) {
      EXPECT_NE(std::string(e.what()).find("cut short"), std::string::npos) << e.what();
    }
  }
}

TEST_F(McapSummaryTest, RefusesAFooterThatPointsOutsideTheFile) {
  std::string bytes = read_all(written());
  // The footer's summary start: the 8 bytes after its opcode and length, before the magic.
  const std::size_t summary_start_at = bytes.size() - 8 - 29 + 9;
  for (std::size_t i = 0; i < 8; ++i) bytes[summary_start_at + i] = '\xff';
  const auto path = with_content("bad_footer.mcap", bytes);
  EXPECT_THROW(read_mcap_summary(path), McapFormatError);
}

TEST_F(McapSummaryTest, RefusesAFileWithoutASummary) {
  std::string bytes = read_all(written());
  const std::size_t summary_start_at = bytes.size() - 8 - 29 + 9;
  for (std::size_t i = 0; i < 16; ++i)
    bytes[summary_start_at + i] = '\0';  // no summary, no offsets
  const auto path = with_content("no_summary.mcap", bytes);
  try {
    read_mcap_summary(path);
    ADD_FAILURE() << "read";
  } catch (const McapFormatError& e) {
    EXPECT_NE(std::string(e.what()).find("without a summary section"), std::string::npos);
  }
}

}  // namespace
}  // namespace skyfuse::record
