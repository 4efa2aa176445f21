#include "skyfuse/registration/bias_trace.hpp"

#include <gtest/gtest.h>

namespace skyfuse {
namespace {

// A radar's range estimate closing in on its truth (100 m): off by 50, 31, 5, 25, 3, 1 m with a
// σ of 10 m each round; its clock, held too, always 0.1 s off with a σ of 1 s.
BiasTrace closing_in() {
  BiasTrace trace;
  trace.station_id = 4;
  trace.estimated = {true, false, false, true};
  trace.truth.range_m = 100.0;
  trace.truth.azimuth_rad = 0.5;  // not estimated: never judged
  for (const double off : {50.0, 31.0, 5.0, 25.0, 3.0, 1.0}) {
    SensorBias estimate;
    estimate.range_m = 100.0 + off;
    estimate.time_s = 0.1;
    SensorBias sigma;
    sigma.range_m = 10.0;
    sigma.time_s = 1.0;
    trace.estimate.push_back(estimate);
    trace.sigma.push_back(sigma);
  }
  return trace;
}

TEST(BiasTrace, JudgesOnlyTheEntriesItEstimates) {
  const BiasTrace trace = closing_in();
  EXPECT_FALSE(within_sigmas(trace, 0, 2.0));
  EXPECT_TRUE(within_sigmas(trace, 2, 2.0));
  EXPECT_FALSE(within_sigmas(trace, 3, 2.0)) << "25 m off is beyond 2 sigma of 10 m";
  EXPECT_TRUE(within_sigmas(trace, 3, 3.0));
  EXPECT_EQ(bias_entry(trace.truth, 0), 100.0);
  EXPECT_EQ(bias_entry(trace.estimate[0], 3), 0.1);
}

TEST(BiasTrace, ConvergesFromTheRoundItStaysWithinOn) {
  BiasTrace trace = closing_in();
  EXPECT_EQ(converged_from(trace, 2.0), 4) << "round 3 left the band";
  EXPECT_EQ(converged_from(trace, 3.0), 2);
  trace.estimate.back().time_s = 3.0;  // the clock leaves it in the last round
  EXPECT_EQ(converged_from(trace, 2.0), -1);
}

}  // namespace
}  // namespace skyfuse
