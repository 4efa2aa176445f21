// FSPECs, item lengths, data blocks: the framing every category shares.
#include <gtest/gtest.h>

#include "skyfuse/asterix/data_block.hpp"
#include "skyfuse/asterix/fspec.hpp"
#include "skyfuse/asterix/item_format.hpp"
#include "skyfuse/asterix/uap.hpp"

namespace skyfuse::asterix {
namespace {

using Kind = ItemFormat::Kind;

TEST(AsterixFspec, SevenFrnsAnOctetWithFxOnAllButTheLast) {
  Bytes out;
  const unsigned one[] = {1};
  append_fspec(out, one);
  EXPECT_EQ(out, Bytes{0x80});  // FRN 1 is bit 8 of the first octet

  out.clear();
  const unsigned seven_eight[] = {7, 8};
  append_fspec(out, seven_eight);
  EXPECT_EQ(out, (Bytes{0x03, 0x80}));  // FRN 7 is bit 2, then FX; FRN 8 opens octet 2

  out.clear();
  const unsigned twenty_seven[] = {27, 1};
  append_fspec(out, twenty_seven);
  // FRN 27 is the 6th bit of octet 4 (FRNs 22-28): 0x80 >> 5 = 0x04.
  EXPECT_EQ(out, (Bytes{0x81, 0x01, 0x01, 0x04}));
}

TEST(AsterixFspec, ReadsBackWhatWasWrittenAndRefusesAnOpenChain) {
  const Bytes fspec{0xBF, 0x5D, 0x11, 0x04, 0xAA};
  const auto read = read_fspec(fspec);
  ASSERT_TRUE(read);
  EXPECT_EQ(read->octets, 4u);
  EXPECT_EQ(read->present, (std::vector<unsigned>{1, 3, 4, 5, 6, 7, 9, 11, 12, 13, 18, 27}));
  EXPECT_FALSE(read_fspec(Bytes{0x81, 0x01}));  // FX on the last octet there is
  EXPECT_FALSE(read_fspec(Bytes{}));
}

TEST(AsterixItemLength, EveryShapeAndItsRefusals) {
  const auto length = [](const Bytes& bytes, ItemFormat format) {
    return item_length(bytes, format);
  };
  EXPECT_EQ(std::get<std::size_t>(length({1, 2, 3}, {Kind::fixed, 2, {}})), 2u);
  EXPECT_EQ(std::get<Refusal>(length({1}, {Kind::fixed, 2, {}})), Refusal::item_truncated);
  // Extended: parts while FX; at most 3 parts here.
  EXPECT_EQ(std::get<std::size_t>(length({0x01, 0x01, 0x00}, {Kind::extended, 3, {}})), 3u);
  EXPECT_EQ(std::get<Refusal>(length({0x01, 0x01, 0x01, 0x00}, {Kind::extended, 3, {}})),
            Refusal::item_malformed);
  EXPECT_EQ(std::get<Refusal>(length({0x01}, {Kind::extended, 3, {}})), Refusal::item_truncated);
  // Repetitive: REP = 2 elements of 3 octets.
  EXPECT_EQ(std::get<std::size_t>(length({2, 0, 0, 0, 0, 0, 0}, {Kind::repetitive, 3, {}})), 7u);
  EXPECT_EQ(std::get<Refusal>(length({2, 0, 0, 0}, {Kind::repetitive, 3, {}})),
            Refusal::item_truncated);
  // Repetitive with FX: 3-octet elements, FX in each one's last octet.
  EXPECT_EQ(std::get<std::size_t>(length({0, 0, 1, 0, 0, 0}, {Kind::repetitive_fx, 3, {}})), 6u);
  // Explicit: LEN counts itself.
  EXPECT_EQ(std::get<std::size_t>(length({3, 9, 9, 9}, {Kind::explicit_len, 0, {}})), 3u);
  EXPECT_EQ(std::get<Refusal>(length({0}, {Kind::explicit_len, 0, {}})), Refusal::item_malformed);
  // Compound: I062/500 with APC (4) and ATV (2): primary 0x84.
  const auto& i500 = uap_cat062()[frn_of(uap_cat062(), 500) - 1].format;
  EXPECT_EQ(std::get<std::size_t>(length({0x84, 0, 1, 0, 2, 3, 4}, i500)), 7u);
  EXPECT_EQ(std::get<Refusal>(length({0x84, 0, 1, 0, 2, 3}, i500)), Refusal::item_truncated);
  // I062/500 has 8 subfields: subfield 9 (second octet, 0x40) is not defined.
  EXPECT_EQ(std::get<Refusal>(length({0x01, 0x40, 0}, i500)), Refusal::undefined_item);
}

TEST(AsterixUap, EditionsHaveTheirItemsWhereTheStandardPutsThem) {
  EXPECT_EQ(uap_cat062().size(), 35u);
  EXPECT_EQ(frn_of(uap_cat062(), 10), 1u);
  EXPECT_EQ(frn_of(uap_cat062(), 15), 3u);  // FRN 2 is spare in ed. 1.19
  EXPECT_EQ(frn_of(uap_cat062(), 380), 11u);
  EXPECT_EQ(frn_of(uap_cat062(), 500), 27u);
  EXPECT_EQ(uap_cat048().size(), 28u);
  EXPECT_EQ(frn_of(uap_cat048(), 161), 11u);
  EXPECT_EQ(uap_cat021().size(), 49u);
  EXPECT_EQ(frn_of(uap_cat021(), 131), 7u);
  EXPECT_EQ(frn_of(uap_cat021(), 160), 26u);
}

TEST(AsterixDataBlock, CatLenThenRecords) {
  const std::vector<Bytes> records{{0x80, 0x01, 0x02}, {0x80, 0x03, 0x04}};
  const auto block = encode_block(48, records);
  ASSERT_TRUE(block);
  // CAT 48 = 0x30; LEN = 3 + 3 + 3 = 9, big-endian.
  EXPECT_EQ(block.bytes, (Bytes{0x30, 0x00, 0x09, 0x80, 0x01, 0x02, 0x80, 0x03, 0x04}));
}

TEST(AsterixDataBlock, RefusesMoreThanLenHolds) {
  const std::vector<Bytes> records{Bytes(40000, 0), Bytes(30000, 0)};
  const auto block = encode_block(62, records);
  EXPECT_FALSE(block);
}

TEST(AsterixDataBlock, SplitsRecordsIntoBlocksOfAtMostTheGivenSize) {
  const std::vector<Bytes> records(10, Bytes(100, 0x80));
  std::optional<EncodeError> error;
  const auto blocks = encode_blocks(62, records, 3 + 4 * 100 + 50, error);
  ASSERT_FALSE(error);
  ASSERT_EQ(blocks.size(), 3u);  // 4 + 4 + 2 records
  EXPECT_EQ(blocks[0].size(), 403u);
  EXPECT_EQ(blocks[2].size(), 203u);
  encode_blocks(62, records, 50, error);
  EXPECT_TRUE(error);
}

TEST(AsterixDataBlock, SplitsADatagramIntoItsBlocks) {
  const Bytes datagram{0x30, 0x00, 0x05, 0x80, 0x01, 0x3E, 0x00, 0x04, 0x00};
  RefusalCounts refusals;
  const auto blocks = split_blocks(datagram, refusals);
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0].category, 48);
  EXPECT_EQ(blocks[0].records.size(), 2u);
  EXPECT_EQ(blocks[1].category, 62);
  EXPECT_EQ(refusals.total(), 0u);
}

}  // namespace
}  // namespace skyfuse::asterix
