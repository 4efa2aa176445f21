// Rounding and range of ASTERIX fields: nearest LSB with ties away from zero, a value the field
// cannot hold refused (never wrapped), two's complement both ways.
#include "skyfuse/asterix/quantity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "skyfuse/asterix/byte_reader.hpp"
#include "skyfuse/asterix/byte_writer.hpp"

namespace skyfuse::asterix {
namespace {

constexpr auto kSigned = Signedness::twos_complement;
constexpr auto kUnsigned = Signedness::unsigned_field;

TEST(AsterixQuantity, RoundsToTheNearestLsbWithTiesAwayFromZero) {
  EXPECT_EQ(quantise(1.24, 0.5, 16, kSigned), 2);  // 2.48 LSB
  EXPECT_EQ(quantise(1.26, 0.5, 16, kSigned), 3);  // 2.52 LSB
  EXPECT_EQ(quantise(1.25, 0.5, 16, kSigned), 3);  // 2.5: away from zero
  EXPECT_EQ(quantise(-1.25, 0.5, 16, kSigned), -3);
}

TEST(AsterixQuantity, RefusesWhatTheFieldCannotHold) {
  // 8 bits signed hold [-128, 127] LSB; 127.4 rounds to 127, 127.5 to 128: refused.
  EXPECT_EQ(quantise(127.4, 1.0, 8, kSigned), 127);
  EXPECT_FALSE(quantise(127.5, 1.0, 8, kSigned));
  EXPECT_EQ(quantise(-128.0, 1.0, 8, kSigned), -128);
  EXPECT_FALSE(quantise(-128.6, 1.0, 8, kSigned));
  EXPECT_EQ(quantise(255.0, 1.0, 8, kUnsigned), 255);
  EXPECT_FALSE(quantise(256.0, 1.0, 8, kUnsigned));
  EXPECT_FALSE(quantise(-0.6, 1.0, 8, kUnsigned));
  EXPECT_FALSE(quantise(std::nan(""), 1.0, 8, kSigned));
  EXPECT_FALSE(quantise(std::numeric_limits<double>::infinity(), 1.0, 32, kSigned));
  EXPECT_FALSE(quantise(1e300, 1.0, 32, kSigned));
}

TEST(AsterixQuantity, ClampsOnlyWhereAskedAndNeverBelowZero) {
  EXPECT_EQ(quantise_clamped(1e9, 0.5, 16), 65535);
  EXPECT_EQ(quantise_clamped(std::numeric_limits<double>::infinity(), 0.5, 16), 65535);
  EXPECT_EQ(quantise_clamped(3.0, 0.5, 16), 6);
  EXPECT_FALSE(quantise_clamped(-1.0, 0.5, 16));
  EXPECT_FALSE(quantise_clamped(std::nan(""), 0.5, 16));
}

TEST(AsterixQuantity, TwosComplementBothWays) {
  EXPECT_EQ(field_bits(-1, 24), 0xFFFFFFu);
  EXPECT_EQ(field_bits(-2001, 24), 0xFFF82Fu);
  EXPECT_EQ(sign_extend(0xFFF82Fu, 24), -2001);
  EXPECT_EQ(sign_extend(0x7FFFu, 16), 32767);
  EXPECT_EQ(sign_extend(0x8000u, 16), -32768);
  EXPECT_EQ(sign_extend(0x3FEBu, 14), -21);
  EXPECT_EQ(sign_extend(0x80000000u, 32), -2147483648LL);
}

TEST(AsterixByteWriter, WritesBigEndianAndKeepsTheFirstError) {
  ByteWriter out;
  out.put(0x0102, 2);
  out.put_quantity("a", -1.0, 1.0, 3, kSigned);
  EXPECT_EQ(out.bytes(), (Bytes{0x01, 0x02, 0xFF, 0xFF, 0xFF}));
  out.put_quantity("first", 300.0, 1.0, 1, kUnsigned);
  out.put_quantity("second", 300.0, 1.0, 1, kUnsigned);
  const auto result = std::move(out).finish();
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error->item, "first");
  EXPECT_TRUE(result.bytes.empty());
}

TEST(AsterixByteReader, NeverReadsPastItsSpan) {
  const Bytes bytes{0x12, 0x34, 0x56};
  ByteReader in(bytes);
  EXPECT_EQ(in.get(2), 0x1234u);
  EXPECT_FALSE(in.overrun());
  EXPECT_EQ(in.get(2), 0u);  // one octet left: refused, not read
  EXPECT_TRUE(in.overrun());
  EXPECT_EQ(in.remaining(), 0u);
  EXPECT_TRUE(in.take(1).empty());
}

}  // namespace
}  // namespace skyfuse::asterix
