// Each kind of malformed input refused and counted, what it costs as refusal.hpp says, and
// nothing read outside the datagram.
#include <gtest/gtest.h>

#include "asterix_samples.hpp"
#include "skyfuse/asterix/data_block.hpp"
#include "skyfuse/asterix/datagram.hpp"

namespace skyfuse::asterix {
namespace {

using testing::sample_plot;
using testing::sample_track;

Bytes track_record() {
  return encode_cat062_record(sample_track()).bytes;
}

// A CAT062 block of these records, LEN set to what they hold.
Bytes cat062_block(const std::vector<Bytes>& records) {
  return encode_block(62, records).bytes;
}

Bytes concat(Bytes a, const Bytes& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The one refusal of a datagram, which must be of `kind`.
void expect_only(const Decoded& decoded, Refusal kind) {
  EXPECT_EQ(decoded.refusals[kind], 1u) << refusal_name(kind);
  EXPECT_EQ(decoded.refusals.total(), 1u);
}

TEST(AsterixRefusals, ATruncatedBlockHeader) {
  const auto decoded = decode_datagram(Bytes{62, 0x00});
  expect_only(decoded, Refusal::truncated_block);
}

TEST(AsterixRefusals, LenShorterThanARecordOrPastTheDatagram) {
  expect_only(decode_datagram(Bytes{62, 0x00, 0x03}), Refusal::length_mismatch);
  auto block = cat062_block({track_record()});
  block.pop_back();  // LEN now says one octet more than there is
  expect_only(decode_datagram(block), Refusal::length_mismatch);
}

TEST(AsterixRefusals, AnUnknownCategoryCostsOnlyItsBlock) {
  const RadarPlot plots[] = {sample_plot()};
  const auto datagram = concat(Bytes{1, 0x00, 0x05, 0x80, 0x00}, encode_cat048(plots).bytes);
  const auto decoded = decode_datagram(datagram);
  expect_only(decoded, Refusal::unknown_category);
  EXPECT_EQ(decoded.plots.size(), 1u);  // the next block, found through LEN
}

TEST(AsterixRefusals, AnFspecThatRunsPastTheBlock) {
  // The first record is whole; the second is an FSPEC octet with FX set and nothing after it.
  const auto decoded = decode_datagram(cat062_block({track_record(), Bytes{0xFF}}));
  expect_only(decoded, Refusal::fspec_past_end);
  EXPECT_EQ(decoded.tracks.size(), 1u);  // the records before it are kept
}

TEST(AsterixRefusals, AnFspecNamingASpareOrUndefinedFrn) {
  // FRN 2 of CAT062 ed. 1.19 is spare.
  expect_only(decode_datagram(cat062_block({Bytes{0x40}})), Refusal::undefined_item);
  // FRN 36: the UAP ends at 35 (SP).
  expect_only(decode_datagram(cat062_block({Bytes{0x01, 0x01, 0x01, 0x01, 0x01, 0x80}})),
              Refusal::undefined_item);
}

TEST(AsterixRefusals, AnItemCutShortByTheBlocksEnd) {
  auto record = track_record();
  record.pop_back();  // I062/080, the last item, loses its octet
  const auto decoded = decode_datagram(cat062_block({track_record(), record}));
  expect_only(decoded, Refusal::item_truncated);
  EXPECT_EQ(decoded.tracks.size(), 1u);
}

TEST(AsterixRefusals, AnItemWhoseOwnStructureIsWrong) {
  // I062/080 (6 parts at most in ed. 1.19) with FX set on its sixth part.
  auto record = track_record();
  record.back() = 0x01;
  for (int i = 0; i < 6; ++i) record.push_back(0x01);
  expect_only(decode_datagram(cat062_block({record})), Refusal::item_malformed);
}

TEST(AsterixRefusals, AValueOutOfRangeCostsOnlyItsRecord) {
  auto bad = track_record();
  // I062/070 follows FSPEC (2), 010 (2) and 015 (1): 0xFFFFFF/128 s is past midnight.
  bad[5] = bad[6] = bad[7] = 0xFF;
  const auto decoded = decode_datagram(cat062_block({bad, track_record()}));
  expect_only(decoded, Refusal::value_out_of_range);
  EXPECT_EQ(decoded.tracks.size(), 1u);  // the next record, whose start was known
}

TEST(AsterixRefusals, ReservedCodesAreOutOfRange) {
  auto record = encode_cat021_record(testing::sample_report()).bytes;
  // I021/040 follows the 3-octet FSPEC (FRNs 1 to 17) and I021/010: ATP 4 (reserved) in bits
  // 8-6.
  record[5] = static_cast<std::uint8_t>(record[5] | 0x80);
  const std::vector<Bytes> records{record};
  expect_only(decode_datagram(encode_block(21, records).bytes), Refusal::value_out_of_range);
}

TEST(AsterixRefusals, ARecordWithoutAnItemTheDecoderNeeds) {
  // I062/010 alone: no track number, time or position.
  expect_only(decode_datagram(cat062_block({Bytes{0x80, 0x19, 0x64}})), Refusal::missing_item);
}

TEST(AsterixRefusals, CountsAddUpOverAFeed) {
  Decoded feed;
  decode_datagram(Bytes{62, 0x00}, feed);
  decode_datagram(Bytes{62, 0x00}, feed);
  decode_datagram(cat062_block({track_record()}), feed);
  EXPECT_EQ(feed.refusals[Refusal::truncated_block], 2u);
  EXPECT_EQ(feed.tracks.size(), 1u);
  EXPECT_EQ(refusal_name(Refusal::fspec_past_end), "fspec_past_end");
}

TEST(AsterixRefusals, EveryPrefixOfAValidDatagramDecodesWithoutHarm) {
  // Cut a datagram of all three categories at every length, and flip every bit of it: the
  // decoder refuses or reads, and ASan/UBSan (the fuzz build) or a crash would show otherwise.
  auto track = sample_track();
  track.address = 0x4CA2B3;
  track.accuracy = TrackAccuracy{};
  const SystemTrack tracks[] = {track, sample_track()};
  const RadarPlot plots[] = {sample_plot()};
  const AdsbReport reports[] = {testing::sample_report()};
  const auto datagram = concat(concat(encode_cat062(tracks).bytes, encode_cat048(plots).bytes),
                               encode_cat021(reports).bytes);
  const auto whole = decode_datagram(datagram);
  EXPECT_EQ(whole.tracks.size() + whole.plots.size() + whole.reports.size(), 4u);
  for (std::size_t n = 0; n < datagram.size(); ++n) {
    const auto decoded = decode_datagram(std::span(datagram).first(n));
    EXPECT_LE(decoded.tracks.size() + decoded.plots.size() + decoded.reports.size(), 4u);
  }
  for (std::size_t bit = 0; bit < datagram.size() * 8; ++bit) {
    auto flipped = datagram;
    flipped[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
    decode_datagram(flipped);
  }
}

}  // namespace
}  // namespace skyfuse::asterix
