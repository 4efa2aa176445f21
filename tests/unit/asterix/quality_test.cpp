// ADS-B's accuracy categories (asterix/quality.hpp) against DO-260B's table.
#include "skyfuse/asterix/quality.hpp"

#include <gtest/gtest.h>

namespace skyfuse::asterix {
namespace {

TEST(AdsbQualityCategories, NacpIsTheBestBoundThatHoldsTheError) {
  EXPECT_EQ(nacp_of_epu(2.9), 11);
  EXPECT_EQ(nacp_of_epu(3.0), 10) << "a bound is strict: < 3 m";
  EXPECT_EQ(nacp_of_epu(25.0), 9);
  EXPECT_EQ(nacp_of_epu(15.0 * kHorizontal95), 8) << "a σ of 15 m: 36.7 m at 95 %";
  EXPECT_EQ(nacp_of_epu(0.2 * 1852.0), 6);
  EXPECT_EQ(nacp_of_epu(9.0 * 1852.0), 1);
  EXPECT_EQ(nacp_of_epu(11.0 * 1852.0), 0) << "unknown";
  EXPECT_DOUBLE_EQ(*epu_of_nacp(9), 30.0);
  EXPECT_DOUBLE_EQ(*epu_of_nacp(8), 92.6);
  EXPECT_FALSE(epu_of_nacp(0).has_value());
  EXPECT_FALSE(epu_of_nacp(12).has_value());
  for (std::uint8_t nacp = 1; nacp <= 11; ++nacp) {
    EXPECT_EQ(nacp_of_epu(*epu_of_nacp(nacp) * 0.999), nacp) << int(nacp);
  }
}

TEST(AdsbQualityCategories, NacvIsTheBestBoundThatHoldsTheVelocityError) {
  EXPECT_EQ(nacv_of_error(0.2), 4);
  EXPECT_EQ(nacv_of_error(2.0 * kHorizontal95), 1) << "a σ of 2 m/s: 4.9 m/s at 95 %";
  EXPECT_EQ(nacv_of_error(12.0), 0);
  EXPECT_DOUBLE_EQ(*error_of_nacv(2), 3.0);
  EXPECT_FALSE(error_of_nacv(5).has_value());
}

}  // namespace
}  // namespace skyfuse::asterix
