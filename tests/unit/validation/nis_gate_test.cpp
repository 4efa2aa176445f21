#include "skyfuse/validation/nis_gate.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include "skyfuse/metrics/chi_square.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"

namespace skyfuse {
namespace {

GaussianState<9> prior() {
  GaussianState<9> p;
  p.mean << -1200.0, -300.0, 450.0, 20.0, 5.0, 0.0, 0.0, 0.0, 0.0;
  p.covariance = Covariance<9>::Identity();
  return p;
}

const RangeAzimuthElevation<9> kSensor(Vector3(100.0, 200.0, 0.0));
const Covariance<3> kNoise = Vector3(1.0, 1e-4, 1e-4).asDiagonal();

TEST(NisGate, NisIsTheInnovationWeightedByTheInnovationCovariance) {
  const GaussianState<9> x = prior();
  const Vector3 z = kSensor.predict(x.mean) + Vector3(2.0, 0.01, -0.02);
  const Matrix<3, 9> h = kSensor.jacobian(x.mean);
  const Covariance<3> s = h * x.covariance * h.transpose() + kNoise;
  const Vector3 nu = kSensor.residual(z, kSensor.predict(x.mean));
  const double expected = nu.dot(s.inverse() * nu);
  ASSERT_TRUE(measurement_nis(x, kSensor, z, kNoise).has_value());
  EXPECT_NEAR(*measurement_nis(x, kSensor, z, kNoise), expected, 1e-9 * expected);
}

TEST(NisGate, RefusesOnlyWhatLiesBeyondTheChiSquareQuantile) {
  const NisGate gate = NisGate::at_probability(0.9999);
  EXPECT_NEAR(gate.threshold(3), chi_square_quantile(0.9999, 3.0), 1e-12);
  EXPECT_NEAR(gate.threshold(3), 21.108, 1e-3);  // chi^2(3) at 0.9999, from tables
  const GaussianState<9> x = prior();
  const Vector3 exact = kSensor.predict(x.mean);
  EXPECT_FALSE(gate.refuses(x, kSensor, exact, kNoise));
  // 50 m off in range against sqrt(S_rr) of about 1.4 m: NIS in the thousands.
  EXPECT_TRUE(gate.refuses(x, kSensor, exact + Vector3(50.0, 0.0, 0.0), kNoise));
  EXPECT_FALSE(NisGate().refuses(x, kSensor, exact + Vector3(50.0, 0.0, 0.0), kNoise))
      << "no gate: everything passes";
  EXPECT_THROW(NisGate::at_probability(1.0), std::invalid_argument);
  EXPECT_THROW(NisGate::at_probability(0.0), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse
