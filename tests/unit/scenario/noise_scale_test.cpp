#include <gtest/gtest.h>

#include "skyfuse/scenario/measurement_simulation.hpp"

namespace skyfuse {
namespace {

TEST(NoiseScale, PaperRuleNeverYieldsANonPositiveVariance) {
  // 1 + delta with delta ~ N(0,1) is <= 0 about 16 % of the time; the rule must never return it.
  for (double floor : {1e-6, 0.1, 0.5, 1.0}) {
    const NoiseScaleConfig config{NoiseScaleConfig::Model::kPaper, floor};
    for (std::uint64_t run = 0; run < 20000; ++run) {
      const double scale = draw_noise_scale(config, 99, run, static_cast<int>(run % 13) + 1);
      ASSERT_GE(scale, floor) << "run " << run;
      ASSERT_GT(scale, 0.0);
    }
  }
}

TEST(NoiseScale, PaperRuleIsTheTruncatedNormalAboveTheFloor) {
  // Conditional mean of 1 + delta given 1 + delta >= 0.1: 1 + phi(-0.9) / (1 - Phi(-0.9)).
  const NoiseScaleConfig config{NoiseScaleConfig::Model::kPaper, 0.1};
  double sum = 0.0;
  constexpr int kDraws = 200000;
  for (int i = 0; i < kDraws; ++i)
    sum += draw_noise_scale(config, 7, static_cast<std::uint64_t>(i), 1);
  const double expected = 1.0 + 0.266085 / 0.815940;
  EXPECT_NEAR(sum / kDraws, expected, 0.005);
}

TEST(NoiseScale, NoneModelKeepsTheNominalNoise) {
  const NoiseScaleConfig config{NoiseScaleConfig::Model::kNone, 0.1};
  EXPECT_EQ(draw_noise_scale(config, 1, 2, 3), 1.0);
}

TEST(NoiseScale, IsAPureFunctionOfSeedRunAndStation) {
  const NoiseScaleConfig config;
  EXPECT_EQ(draw_noise_scale(config, 5, 6, 7), draw_noise_scale(config, 5, 6, 7));
  EXPECT_NE(draw_noise_scale(config, 5, 6, 7), draw_noise_scale(config, 5, 6, 8));
  EXPECT_NE(draw_noise_scale(config, 5, 6, 7), draw_noise_scale(config, 5, 7, 7));
  EXPECT_NE(draw_noise_scale(config, 5, 6, 7), draw_noise_scale(config, 4, 6, 7));
}

}  // namespace
}  // namespace skyfuse
