#include "skyfuse/metrics/chi_square.hpp"

#include <gtest/gtest.h>

namespace skyfuse {
namespace {

// Reference quantiles from standard chi-square tables (e.g. NIST/SEMATECH e-Handbook 1.3.6.7.4).
TEST(ChiSquare, QuantilesMatchTables) {
  EXPECT_NEAR(chi_square_quantile(0.975, 9), 19.023, 1e-3);
  EXPECT_NEAR(chi_square_quantile(0.025, 9), 2.700, 1e-3);
  EXPECT_NEAR(chi_square_quantile(0.95, 3), 7.815, 1e-3);
  EXPECT_NEAR(chi_square_quantile(0.05, 3), 0.352, 1e-3);
  EXPECT_NEAR(chi_square_quantile(0.99, 1), 6.635, 1e-3);
  EXPECT_NEAR(chi_square_quantile(0.5, 100), 99.334, 1e-3);
}

TEST(ChiSquare, CdfInvertsTheQuantile) {
  for (double dof : {1.0, 3.0, 9.0, 450.0, 9000.0}) {
    for (double p : {0.001, 0.025, 0.5, 0.975, 0.999}) {
      EXPECT_NEAR(chi_square_cdf(chi_square_quantile(p, dof), dof), p, 1e-10)
          << "dof " << dof << " p " << p;
    }
  }
}

TEST(ChiSquare, AverageBandNarrowsAroundTheDegreesOfFreedom) {
  // 9-dof NEES averaged over 50 runs: chi^2(450) quantiles / 50. The Wilson-Hilferty
  // approximation k (1 - 2/(9k) +- 1.96 sqrt(2/(9k)))^3, good to ~1e-3 here, gives
  // [393.12, 510.66] / 50.
  const ChiSquareBand band50 = average_chi_square_band(9, 50);
  EXPECT_NEAR(band50.lower, 7.862, 0.005);
  EXPECT_NEAR(band50.upper, 10.213, 0.005);
  const ChiSquareBand band1000 = average_chi_square_band(9, 1000);
  EXPECT_GT(band1000.lower, band50.lower);
  EXPECT_LT(band1000.upper, band50.upper);
  EXPECT_TRUE(band1000.contains(9.0));
}

TEST(ChiSquare, RefusesProbabilitiesOutsideTheOpenUnitInterval) {
  EXPECT_THROW(chi_square_quantile(0.0, 3), std::invalid_argument);
  EXPECT_THROW(chi_square_quantile(1.0, 3), std::invalid_argument);
  EXPECT_THROW(chi_square_quantile(0.5, 0), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse
