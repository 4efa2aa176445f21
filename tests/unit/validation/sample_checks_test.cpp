#include "skyfuse/validation/sample_checks.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <limits>
#include <numbers>

#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"

namespace skyfuse {
namespace {

using Observation = StationObservation<RangeAzimuthElevation<9>>;

// A real increment: one station's range/azimuth/elevation about a prior.
InformationIncrement<9> real_increment() {
  GaussianState<9> prior;
  prior.mean << -1200.0, -300.0, 450.0, 20.0, 5.0, 0.0, 0.0, 0.0, 0.0;
  prior.covariance = Covariance<9>::Identity();
  const RangeAzimuthElevation<9> sensor(Vector3(100.0, 200.0, 0.0));
  const Vector3 z = sensor.predict(prior.mean);
  const Covariance<3> noise = Vector3(1.0, 1e-4, 1e-4).asDiagonal();
  InformationIncrement<9> out;
  EXPECT_EQ(compute_increment(3, prior, sensor, z, noise, out), NumericalStatus::kOk);
  return out;
}

Observation real_observation() {
  Observation o;
  o.station_id = 3;
  o.sensor = RangeAzimuthElevation<9>(Vector3(100.0, 200.0, 0.0));
  o.z = Vector3(1500.0, 2.5, 0.3);
  o.noise = Vector3(1.0, 1e-4, 1e-4).asDiagonal();
  return o;
}

TEST(SampleChecks, AcceptsARealIncrement) {
  EXPECT_EQ(check_increment(real_increment()), std::nullopt);
}

TEST(SampleChecks, RefusesNonFiniteIncrements) {
  InformationIncrement<9> nan_q = real_increment();
  nan_q.delta_information(4, 7) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(check_increment(nan_q), DropKind::kNonFinite);
  InformationIncrement<9> inf_y = real_increment();
  inf_y.delta_vector(8) = std::numeric_limits<double>::infinity();
  EXPECT_EQ(check_increment(inf_y), DropKind::kNonFinite);
}

TEST(SampleChecks, RefusesAnIncrementWithANegativeDirection) {
  InformationIncrement<9> bad = real_increment();
  bad.delta_information(5, 5) = -1e-3;  // an information "loss" along vz
  EXPECT_EQ(check_increment(bad), DropKind::kNotPositive);
  // Negating a real one makes it negative semi-definite.
  InformationIncrement<9> negated = real_increment();
  negated.delta_information = -negated.delta_information;
  EXPECT_EQ(check_increment(negated), DropKind::kNotPositive);
}

TEST(SampleChecks, JudgesAnIncrementNearTheLargestDoubleWithoutOverflow) {
  // Found by the fuzzer: eigenvalues of +-1.4 * DBL_MAX overflow to +-Inf, and the tolerance
  // -1e-9 * Inf let the indefinite matrix through. Such sizes are now out of range; the
  // eigenvalue test itself is scaled, so it judges the largest allowed entries correctly too.
  constexpr double kMax = std::numeric_limits<double>::max();
  InformationIncrement<9> indefinite;
  indefinite.delta_information.topLeftCorner<2, 2>() << kMax, kMax, kMax, -kMax;
  EXPECT_EQ(check_increment(indefinite), DropKind::kOutOfRange);
  InformationIncrement<9> at_limit;
  at_limit.delta_information.topLeftCorner<2, 2>() << kMaxInformation, kMaxInformation,
      kMaxInformation, -kMaxInformation;
  EXPECT_EQ(check_increment(at_limit), DropKind::kNotPositive);
  InformationIncrement<9> semi_definite;  // eigenvalues 2 * kMaxInformation and 0
  semi_definite.delta_information.topLeftCorner<2, 2>().setConstant(kMaxInformation);
  EXPECT_EQ(check_increment(semi_definite), std::nullopt);
}

// dQ = V diag(eigenvalues) V^T for a fixed rotation V.
InformationIncrement<9> with_eigenvalues(const Vector<9>& eigenvalues) {
  Covariance<9> seed;
  for (int i = 0; i < 9; ++i) {
    for (int j = 0; j < 9; ++j) seed(i, j) = std::sin(1.0 + i + 9.0 * j);
  }
  const Covariance<9> v = Eigen::HouseholderQR<Covariance<9>>(seed).householderQ();
  InformationIncrement<9> out;
  const Covariance<9> dq = v * eigenvalues.asDiagonal() * v.transpose();
  out.delta_information = dq.selfadjointView<Eigen::Lower>();  // exactly symmetric
  return out;
}

TEST(SampleChecks, DrawsThePositivityLineAtMinusOneBillionthOfTheLargestEigenvalue) {
  // The cheap shifted-Cholesky test settles clear cases; near the line the eigenvalues decide.
  Vector<9> eigenvalues;
  eigenvalues << 1.0, 0.5, 0.2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  EXPECT_EQ(check_increment(with_eigenvalues(eigenvalues)), std::nullopt);
  for (const double inside : {-0.1e-9, -0.5e-9, -0.9e-9}) {
    eigenvalues(8) = inside;
    EXPECT_EQ(check_increment(with_eigenvalues(eigenvalues)), std::nullopt) << inside;
  }
  for (const double outside : {-1.2e-9, -2e-9, -1e-6}) {
    eigenvalues(8) = outside;
    EXPECT_EQ(check_increment(with_eigenvalues(eigenvalues)), DropKind::kNotPositive) << outside;
  }
}

TEST(SampleChecks, AcceptsAZeroIncrement) {
  // A station that saw nothing adds nothing: zero is positive semi-definite.
  EXPECT_EQ(check_increment(InformationIncrement<9>{}), std::nullopt);
}

TEST(SampleChecks, RefusesAContributionWhosePriorCannotBeAdopted) {
  // A peer may adopt the prior an increment travels with, so it is checked like a track.
  PeerContribution<9> good{real_increment(), {}};
  good.prior.covariance = Covariance<9>::Identity();
  EXPECT_EQ(check_contribution(good), std::nullopt);
  PeerContribution<9> nan_prior = good;
  nan_prior.prior.mean(4) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(check_contribution(nan_prior), DropKind::kNonFinite);
  PeerContribution<9> indefinite = good;
  indefinite.prior.covariance(7, 7) = -1.0;
  EXPECT_EQ(check_contribution(indefinite), DropKind::kNotPositive);
  PeerContribution<9> bad_increment = good;
  bad_increment.increment.delta_vector(0) = std::numeric_limits<double>::infinity();
  EXPECT_EQ(check_contribution(bad_increment), DropKind::kNonFinite);
}

TEST(SampleChecks, RefusesMagnitudesThatWouldOverflowTheFusion) {
  // Finite, positive semi-definite, and still impossible: two of these overflow a fused sum.
  InformationIncrement<9> huge = real_increment();
  huge.delta_information(0, 0) = 1e308;
  EXPECT_EQ(check_increment(huge), DropKind::kOutOfRange);
  InformationIncrement<9> huge_y = real_increment();
  huge_y.delta_vector(2) = -1e300;
  EXPECT_EQ(check_increment(huge_y), DropKind::kOutOfRange);
  PeerContribution<9> far{real_increment(), {}};
  far.prior.covariance = Covariance<9>::Identity();
  far.prior.mean(0) = 1e300;
  EXPECT_EQ(check_contribution(far), DropKind::kOutOfRange);
  Observation distant = real_observation();
  distant.sensor = RangeAzimuthElevation<9>(Vector3(1e300, -1e300, 0.0));
  EXPECT_EQ(check_observation(distant), DropKind::kOutOfRange);
}

TEST(SampleChecks, AcceptsARealObservation) {
  EXPECT_EQ(check_observation(real_observation()), std::nullopt);
}

TEST(SampleChecks, RefusesNonFiniteObservations) {
  Observation z = real_observation();
  z.z(1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(check_observation(z), DropKind::kNonFinite);
  Observation r = real_observation();
  r.noise(0, 2) = r.noise(2, 0) = std::numeric_limits<double>::infinity();
  EXPECT_EQ(check_observation(r), DropKind::kNonFinite);
  Observation position = real_observation();
  position.sensor = RangeAzimuthElevation<9>(Vector3(0.0, std::nan(""), 0.0));
  EXPECT_EQ(check_observation(position), DropKind::kNonFinite);
}

TEST(SampleChecks, RefusesANoiseThatIsNotPositiveDefinite) {
  Observation o = real_observation();
  o.noise(2, 2) = 0.0;
  EXPECT_EQ(check_observation(o), DropKind::kNotPositive);
}

TEST(SampleChecks, RefusesMeasurementsTheSensorCannotReport) {
  for (const Vector3& z :
       {Vector3(0.0, 0.1, 0.1), Vector3(-5.0, 0.1, 0.1), Vector3(2.0e6, 0.1, 0.1),
        Vector3(100.0, 3.2, 0.1), Vector3(100.0, 0.1, 1.6), Vector3(100.0, 0.1, -1.6)}) {
    Observation o = real_observation();
    o.z = z;
    EXPECT_EQ(check_observation(o), DropKind::kOutOfRange) << z.transpose();
    EXPECT_EQ(RangeAzimuthElevation<9>::check_reported(z), DropKind::kOutOfRange) << z.transpose();
  }
  // The edges themselves are reportable.
  EXPECT_FALSE(RangeAzimuthElevation<9>::check_reported(
      Vector3(1.0e6, std::numbers::pi, std::numbers::pi / 2.0)));
  EXPECT_FALSE(RangeAzimuthElevation<9>::check_reported(
      Vector3(1e-9, -std::numbers::pi, -std::numbers::pi / 2.0)));
  EXPECT_EQ(RangeAzimuthElevation<9>::check_reported(Vector3(100.0, std::nan(""), 0.1)),
            DropKind::kNonFinite);
}

TEST(SampleChecks, AMeasurementMustComeFromWhereTheScenarioPutsItsStation) {
  StationConfig station;
  station.id = 2;
  station.position_m = Vector3(-450.0, -450.0, 20.0);
  EXPECT_FALSE(check_site(RangeAzimuthElevation<9>(station.position_m), station));
  EXPECT_EQ(
      check_site(RangeAzimuthElevation<9>(station.position_m + Vector3(0.0, 0.0, 1e-3)), station),
      DropKind::kWrongSite);
  EXPECT_EQ(check_site(RangeAzimuthElevation<9>(Vector3::Zero()), station), DropKind::kWrongSite);
}

TEST(SampleChecks, AParticipantsMeasurementMustHaveItsSensorAtItsSite) {
  StationConfig station;
  station.id = 2;
  station.position_m = Vector3(-450.0, -450.0, 20.0);
  station.sensor.kind = "range_azimuth_elevation";
  StationObservation<RangeAzimuthElevation<9>> radar{
      2, RangeAzimuthElevation<9>(station.position_m), Vector3(1500.0, 0.5, 0.3),
      Vector3(1.0, 1e-4, 1e-4).asDiagonal()};
  EXPECT_FALSE(check_station_measurement(radar, &station));
  EXPECT_FALSE(check_station_measurement(radar, nullptr)) << "no participant: content only";
  radar.z(0) = -1.0;
  EXPECT_EQ(check_station_measurement(radar, &station), DropKind::kOutOfRange);
  // The same id reporting as a GPS receiver: not the sensor the scenario gives it.
  StationObservation<PositionVelocity<9>> gps;
  gps.station_id = 2;
  gps.z.setZero();
  gps.noise.setIdentity();
  EXPECT_FALSE(check_observation(gps));
  EXPECT_EQ(check_station_measurement(gps, &station), DropKind::kOutOfRange);
}

TEST(DropKind, NamesAreDistinctSnakeCase) {
  for (std::size_t i = 0; i < kDropKinds; ++i) {
    const std::string_view name = to_string(static_cast<DropKind>(i));
    EXPECT_FALSE(name.empty());
    for (std::size_t j = 0; j < i; ++j) EXPECT_NE(name, to_string(static_cast<DropKind>(j)));
  }
  EXPECT_EQ(to_string(DropKind::kNisGate), "nis_gate");
  EXPECT_EQ(to_string(DropKind::kWrongSite), "wrong_site");
  EXPECT_EQ(to_string(DropKind::kOverlap), "overlap");
}

TEST(SampleChecks, ImmLikelihoodTermsMustBeARealMeasurementsOrAllZero) {
  const InformationIncrement<9> increment = real_increment();
  EXPECT_EQ(check_likelihood_terms({2.5, -18.4, 3}, increment), std::nullopt);
  EXPECT_EQ(check_likelihood_terms({-0.1, -18.4, 3}, increment), DropKind::kOutOfRange);
  EXPECT_EQ(check_likelihood_terms({2.5, -18.4, 17}, increment), DropKind::kOutOfRange);
  EXPECT_EQ(check_likelihood_terms({2.5, 1e4, 3}, increment), DropKind::kOutOfRange);
  EXPECT_EQ(check_likelihood_terms({std::nan(""), -18.4, 3}, increment), DropKind::kNonFinite);
  // Screened out: zero terms go with a zero increment, and only with one.
  InformationIncrement<9> zero = increment;
  zero.delta_information.setZero();
  zero.delta_vector.setZero();
  EXPECT_EQ(check_likelihood_terms({}, zero), std::nullopt);
  EXPECT_EQ(check_likelihood_terms({}, increment), DropKind::kOutOfRange);
  EXPECT_EQ(check_likelihood_terms({0.0, -18.4, 0}, zero), DropKind::kOutOfRange);
}

TEST(SampleChecks, ModeProbabilitiesMustBeADistribution) {
  EXPECT_EQ(check_mode_probabilities(Vector3(0.2, 0.3, 0.5)), std::nullopt);
  EXPECT_EQ(check_mode_probabilities(Vector3(0.2, 0.3, 0.4)), DropKind::kOutOfRange);
  EXPECT_EQ(check_mode_probabilities(Vector3(-0.2, 0.7, 0.5)), DropKind::kOutOfRange);
  EXPECT_EQ(check_mode_probabilities(Vector3(1.5, -0.5, 0.0)), DropKind::kOutOfRange);
  EXPECT_EQ(check_mode_probabilities(Vector3(std::nan(""), 0.5, 0.5)), DropKind::kNonFinite);
}

}  // namespace
}  // namespace skyfuse
