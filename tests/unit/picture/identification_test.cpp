// An identification packs a callsign of up to 8 characters of ICAO's 6-bit set into 64 bits.
#include "skyfuse/picture/identification.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace skyfuse {
namespace {

TEST(Identification, ACallsignPacksIntoItsAsciiOctetsAndBack) {
  // "KLM1023": 4B 4C 4D 31 30 32 33, then a zero octet.
  EXPECT_EQ(identification_of("KLM1023"), 0x4B4C4D3130323300ULL);
  EXPECT_EQ(identification_of("A"), 0x4100000000000000ULL);
  EXPECT_EQ(callsign_of(0x4B4C4D3130323300ULL), "KLM1023");
  for (const char* callsign : {"A", "DLH4AB", "SFF00002", "AB CD", "12345678"}) {
    const auto packed = identification_of(callsign);
    ASSERT_TRUE(packed) << callsign;
    EXPECT_NE(*packed, kNoIdentification);
    EXPECT_EQ(callsign_of(*packed), callsign);
  }
  EXPECT_EQ(callsign_of(kNoIdentification), "");
}

TEST(Identification, TrailingSpacesAndLowerCaseAreTheFilesNotTheCallsigns) {
  EXPECT_EQ(identification_of("DLH4AB  "), identification_of("DLH4AB"));
  EXPECT_EQ(identification_of("ein12"), identification_of("EIN12"));
}

TEST(Identification, WhatAirTrafficsFormatsCannotCarryIsNone) {
  for (const char* refused : {"", "    ", "N-123", "ABCDEFGHI", "É12", "AB\tC"}) {
    EXPECT_FALSE(identification_of(refused)) << "'" << refused << "'";
  }
}

TEST(Identification, AnEmptyListMeansNoneHasOne) {
  const std::vector<Identification> none;
  EXPECT_EQ(identification_at(none, 3), kNoIdentification);
  const std::vector<Identification> some{kNoIdentification, *identification_of("QFA1")};
  EXPECT_EQ(callsign_of(identification_at(some, 1)), "QFA1");
}

}  // namespace
}  // namespace skyfuse
