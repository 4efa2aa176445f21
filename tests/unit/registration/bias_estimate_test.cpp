#include "skyfuse/registration/bias_estimate.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/QR>
#include <cmath>
#include <vector>

#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth.hpp"
#include "skyfuse/models/range_azimuth_altitude.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/random/counter_rng.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {
namespace {

using Radar = RangeAzimuthElevation<kKinematicsDim>;
using Estimate = BiasEstimate<Radar>;

const Vector3 kSite(-20000.0, -15000.0, 50.0);
constexpr SensorBias kTrueBias{
    .range_m = 150.0, .azimuth_rad = 0.002618, .elevation_rad = 0.001745, .time_s = 0.5};

Covariance<3> radar_noise() {
  Covariance<3> r = Covariance<3>::Zero();
  r.diagonal() << 30.0 * 30.0, 0.00087 * 0.00087, 0.0017 * 0.0017;
  return r;
}

// Aircraft `i` of a set spread over the radar's field: position, velocity, no acceleration.
Vector<kKinematicsDim> aircraft(int i) {
  const double bearing = 0.37 * i;
  const double range = 15000.0 + 700.0 * (i % 50);
  Vector<kKinematicsDim> x = Vector<kKinematicsDim>::Zero();
  x.head<3>() = kSite + Vector3(range * std::cos(bearing), range * std::sin(bearing),
                                1000.0 + 90.0 * (i % 40));
  x.segment<3>(3) << 200.0 * std::cos(1.3 * i), 200.0 * std::sin(1.3 * i), 0.0;
  return x;
}

// The biased radar's detection of `x`, drawn as the simulator draws one.
Vector3 biased_detection(const Radar& radar, const Vector<kKinematicsDim>& x, CounterRng& rng) {
  Vector3 z = radar.predict(kinematics_after(x, kTrueBias.time_s)) + offsets_of<Radar>(kTrueBias);
  const Covariance<3> r = radar_noise();
  for (int c = 0; c < 3; ++c) z(c) += std::sqrt(r(c, c)) * rng.normal();
  return z;
}

Estimate::Bias as_vector(const SensorBias& b) {
  return Estimate::Bias(b.range_m, b.azimuth_rad, b.elevation_rad, b.time_s);
}

const Estimate::Bias kPriorStd(500.0, 0.01, 0.01, 5.0);

TEST(BiasEstimate, EstimatesTheOffsetsASensorMeasuresAndItsClock) {
  EXPECT_EQ(BiasEstimate<RangeAzimuthElevation<kKinematicsDim>>::kDim, 4);
  EXPECT_EQ(BiasEstimate<RangeAzimuth<kKinematicsDim>>::kDim, 3);
  EXPECT_EQ(BiasEstimate<RangeAzimuthAltitude<kKinematicsDim>>::kDim, 3);
  EXPECT_EQ(BiasEstimate<PositionVelocity<kKinematicsDim>>::kDim, 1);  // the clock alone
}

// ∂r/∂b against central differences of the simulator's own biased measurement.
TEST(BiasEstimate, ItsBiasJacobianIsTheSimulatorsDerivative) {
  const Radar radar(kSite);
  for (int i = 0; i < 50; ++i) {
    const Vector<kKinematicsDim> x = aircraft(i);
    const Matrix<3, 4> g = Estimate::bias_jacobian(radar.jacobian(x), x);
    const auto measured = [&](const Estimate::Bias& b) {
      return Vector3(radar.predict(kinematics_after(x, b(3))) +
                     offsets_of<Radar>(Estimate::as_sensor_bias(b)));
    };
    for (int k = 0; k < 4; ++k) {
      const double step = k == 0 ? 1.0 : k == 3 ? 1e-3 : 1e-6;
      Estimate::Bias up = Estimate::Bias::Zero();
      Estimate::Bias down = Estimate::Bias::Zero();
      up(k) = step;
      down(k) = -step;
      const Vector3 numeric = (measured(up) - measured(down)) / (2.0 * step);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(g(c, k), numeric(c), 1e-6 * (1.0 + std::abs(numeric(c))))
            << "aircraft " << i << ", column " << k << ", row " << c;
      }
    }
  }
}

// A radar with the offsets and a clock half a second late, seeing 400 aircraft whose
// tracks are known to a metre (as broadcasts make them): its biases come out within 3 sigma,
// and an independent batch least-squares solution (QR of the stacked, whitened rows) gives
// the same estimate.
TEST(BiasEstimate, RecoversARadarsBiasesAndAgreesWithBatchLeastSquares) {
  const Radar radar(kSite);
  Estimate estimate(kPriorStd);
  CounterRng rng({2026, 11, 30, 0, NoiseStream::kMeasurement});
  constexpr int kDetections = 400;
  Eigen::MatrixXd rows(3 * kDetections + 4, 4);
  Eigen::VectorXd values(3 * kDetections + 4);
  for (int i = 0; i < kDetections; ++i) {
    GaussianState<kKinematicsDim> track;
    track.mean = aircraft(i);
    track.covariance = Covariance<kKinematicsDim>::Identity();  // 1 m, 1 m/s, 1 m/s²
    const Vector3 z = biased_detection(radar, track.mean, rng);
    ASSERT_TRUE(estimate.add(radar, track, z, radar_noise()));

    // The batch's rows: S^-1/2 G b = S^-1/2 r, by its own factorisation.
    const Jacobian<3, kKinematicsDim> h = radar.jacobian(track.mean);
    const Covariance<3> s = h * track.covariance * h.transpose() + radar_noise();
    const Eigen::Matrix3d whiten =
        Eigen::LLT<Eigen::Matrix3d>(s).matrixL().solve(Eigen::Matrix3d::Identity());
    rows.block(3 * i, 0, 3, 4) = whiten * Estimate::bias_jacobian(h, track.mean);
    values.segment(3 * i, 3) = whiten * Radar::residual(z, radar.predict(track.mean));
  }
  rows.bottomRows(4) = kPriorStd.cwiseInverse().asDiagonal();
  values.tail(4).setZero();
  EXPECT_EQ(estimate.detections(), static_cast<std::size_t>(kDetections));

  const auto online = estimate.estimate();
  ASSERT_TRUE(online.has_value());
  const Estimate::Bias error = online->mean - as_vector(kTrueBias);
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT(std::abs(error(k)), 3.0 * std::sqrt(online->covariance(k, k)))
        << "entry " << k << ": estimated " << online->mean(k) << ", true "
        << as_vector(kTrueBias)(k);
  }
  const double nees = error.dot(online->covariance.inverse() * error);
  EXPECT_LT(nees, 18.47);  // chi-square(4) at 0.999

  const Eigen::VectorXd batch = rows.householderQr().solve(values);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(batch(k), online->mean(k), 1e-9 * (1.0 + std::abs(batch(k)))) << "entry " << k;
  }
  const SensorBias named = Estimate::as_sensor_bias(online->mean);
  EXPECT_EQ(named.range_m, online->mean(0));
  EXPECT_EQ(named.time_s, online->mean(3));
}

// A 2-D radar has no elevation to offset: its estimate is [range, azimuth, clock].
TEST(BiasEstimate, ATwoDimensionalRadarsBiasHasNoElevation) {
  using Radar2d = RangeAzimuth<kKinematicsDim>;
  const Matrix<2, 3> g = BiasEstimate<Radar2d>::bias_jacobian(
      Radar2d(kSite, HeightBand{0.0, 1000.0}).jacobian(aircraft(3)), aircraft(3));
  EXPECT_EQ(g(0, 0), 1.0);
  EXPECT_EQ(g(1, 1), 1.0);
  EXPECT_EQ(g(0, 1), 0.0);
  const SensorBias named = BiasEstimate<Radar2d>::as_sensor_bias(Vector3(10.0, 0.001, 0.2));
  EXPECT_EQ(named.range_m, 10.0);
  EXPECT_EQ(named.azimuth_rad, 0.001);
  EXPECT_EQ(named.elevation_rad, 0.0);
  EXPECT_EQ(named.time_s, 0.2);
}

}  // namespace
}  // namespace skyfuse
