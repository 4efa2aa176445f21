#include "skyfuse/models/multilateration.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/metrics/chi_square.hpp"
#include "support/numerical_jacobian.hpp"
#include "support/random_problems.hpp"

namespace skyfuse {
namespace {

using Sensor = Multilateration<9>;
using Receivers = Sensor::Receivers;

// A point within `across` of the origin east and north and `height` up, drawn height first
// (one draw at a time: tests/support/draw_last_first.hpp says why).
Vector3 random_point(std::mt19937& rng, double across_m, double low_m, double high_m) {
  std::uniform_real_distribution<double> across(-across_m, across_m);
  std::uniform_real_distribution<double> height(low_m, high_m);
  const double up = height(rng);
  const double north = across(rng);
  return Vector3(across(rng), north, up);
}

// Six receivers over a city: within 10 km of the origin, on roofs and masts 0-150 m up.
Receivers random_ground_receivers(std::mt19937& rng) {
  Receivers sites;
  for (Vector3& s : sites) s = random_point(rng, 10000.0, 0.0, 150.0);
  return sites;
}

Sensor sensor_at(const Receivers& sites, double sigma_m = 1.0) {
  const std::array<double, Sensor::kMeasDim> std_m{sigma_m, sigma_m, sigma_m, sigma_m, sigma_m};
  return Sensor(sites[0], std::span<const Vector3>(sites).subspan(1), std_m);
}

Vector3 random_aircraft(std::mt19937& rng) {
  return random_point(rng, 8000.0, 300.0, 3000.0);
}

double cost_at(const Sensor& sensor, const Vector<5>& z, const Vector3& p, double variance) {
  return (z - sensor.measure_position(p)).squaredNorm() / variance;
}

double lowest_height(const Receivers& sites) {
  double lowest = sites[0].z();
  for (const Vector3& s : sites) lowest = std::min(lowest, s.z());
  return lowest;
}

// An independent minimiser of the same cost over the heights no lower than `floor`: a compass
// (pattern) search that only evaluates the cost, started at the truth, halving its step until
// it is below a micrometre.
Vector3 compass_search(const Sensor& sensor, const Vector<5>& z, Vector3 p, double variance,
                       double floor) {
  double best = cost_at(sensor, z, p, variance);
  for (double step = 256.0; step > 1e-6;) {
    bool moved = false;
    for (int axis = 0; axis < 3; ++axis) {
      for (const double sign : {1.0, -1.0}) {
        Vector3 candidate = p;
        candidate(axis) += sign * step;
        if (candidate.z() < floor) continue;
        const double cost = cost_at(sensor, z, candidate, variance);
        if (cost < best) {
          best = cost;
          p = candidate;
          moved = true;
        }
      }
    }
    if (!moved) step *= 0.5;
  }
  return p;
}

TEST(Multilateration, JacobianMatchesFiniteDifferencesAtRandomPoints) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 300; ++trial) {
    const Sensor sensor = sensor_at(random_ground_receivers(rng));
    Vector<9> x;
    x << random_aircraft(rng), test::random_vector3(rng, -80.0, 80.0),
        test::random_vector3(rng, -5.0, 5.0);
    const Jacobian<5, 9> analytic = sensor.jacobian(x);
    const Jacobian<5, 9> numeric = test::numerical_jacobian(sensor, x);
    for (int row = 0; row < 5; ++row) {
      EXPECT_LE(test::relative_error(analytic.row(row), numeric.row(row)), 1e-6)
          << "row " << row << " at x = " << x.transpose();
    }
  }
}

TEST(Multilateration, MeasuresRangeDifferencesToTheReference) {
  Receivers sites{Vector3(0, 0, 0),  Vector3(3, 0, 0),  Vector3(0, 8, 0),
                  Vector3(0, 0, 20), Vector3(-3, 0, 0), Vector3(0, -8, 0)};
  const Vector<5> z = sensor_at(sites).measure_position(Vector3(0.0, 0.0, 4.0));  // 4 m up
  EXPECT_DOUBLE_EQ(z(0), 5.0 - 4.0);
  EXPECT_DOUBLE_EQ(z(1), std::sqrt(80.0) - 4.0);
  EXPECT_DOUBLE_EQ(z(2), 16.0 - 4.0);
  EXPECT_DOUBLE_EQ(z(3), z(0)) << "the mirror receiver, the same difference";
}

TEST(Multilateration, TheClosedFormStartIsExactForReceiversInAPlane) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 200; ++trial) {
    Receivers sites = random_ground_receivers(rng);
    for (Vector3& s : sites) s.z() = 40.0;
    const Vector3 p = random_aircraft(rng);
    const Vector<5> z = sensor_at(sites).measure_position(p);
    const Vector3 start = multilateration_start(sites, std::span<const double>(z.data(), 5));
    EXPECT_LE((start - p).norm(), 1e-6 * p.norm()) << "trial " << trial;
  }
}

TEST(Multilateration, ExactDifferencesGiveThePositionBack) {
  std::mt19937 rng(21);
  int converged = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Sensor sensor = sensor_at(random_ground_receivers(rng));
    const Vector3 p = random_aircraft(rng);
    const Vector<5> z = sensor.measure_position(p);
    const std::array<double, 5> variances{1.0, 1.0, 1.0, 1.0, 1.0};
    const MultilaterationFix fix =
        solve_multilateration(sensor.receivers(), std::span<const double>(z.data(), 5), variances);
    converged += fix.converged ? 1 : 0;
    EXPECT_LE((fix.position - p).norm(), 1e-4) << "trial " << trial << " at " << p.transpose();
    EXPECT_EQ(sensor.position_of(z), fix.position);
  }
  EXPECT_EQ(converged, 500);
}

TEST(Multilateration, TheNoisyFixIsTheMinimumAnIndependentSearchFinds) {
  std::mt19937 rng(34);
  std::normal_distribution<double> unit;
  const double sigma = 15.0;
  constexpr int kTrials = 1000;
  int same_minimum = 0;
  int other_minimum = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const Sensor sensor = sensor_at(random_ground_receivers(rng), sigma);
    const Vector3 p = random_aircraft(rng);
    Vector<5> z = sensor.measure_position(p);
    for (int i = 0; i < 5; ++i) z(i) += sigma * unit(rng);
    const Vector3 fix = sensor.position_of(z);
    const Vector3 searched =
        compass_search(sensor, z, p, sigma * sigma, lowest_height(sensor.receivers()));
    const double fix_cost = cost_at(sensor, z, fix, sigma * sigma);
    const double searched_cost = cost_at(sensor, z, searched, sigma * sigma);
    // Never a worse minimum than the search's, to a thousandth of the cost (a fix of a far
    // aircraft may stop in its long valley before the step tolerance, at most this far off).
    EXPECT_LE(fix_cost, searched_cost * (1.0 + 1e-3)) << "trial " << trial;
    // Either the search's minimum (to a metre), or another one no worse: ground receivers can
    // leave two minima of almost one cost, one low and one high, and the search from the
    // truth stops in one of them.
    if ((fix - searched).norm() <= 1.0) {
      ++same_minimum;
    } else {
      ++other_minimum;
    }
  }
  // Most fixes are the search's minimum: the comparison checks something.
  EXPECT_GE(same_minimum, kTrials * 9 / 10);
  std::printf("multilateration fixes: %d of %d the independent search's minimum, %d another\n",
              same_minimum, kTrials, other_minimum);
}

// The fix's covariance (H^T R^-1 H)^-1, which a track starts from, holds its errors: the
// average NEES of many noisy fixes of one aircraft lies in chi-square(3)'s 99 % band.
TEST(Multilateration, TheFixsErrorsAreWhatItsCovarianceSays) {
  Receivers sites{Vector3(0, 0, 20),          Vector3(6000, 1000, 60),  Vector3(-4000, 5000, 10),
                  Vector3(-3000, -6000, 120), Vector3(5000, -4000, 35), Vector3(500, 7000, 90)};
  const double sigma = 10.0;
  const Sensor sensor = sensor_at(sites, sigma);
  const Vector3 p(1500.0, 800.0, 1200.0);
  Vector<9> x = Vector<9>::Zero();
  x.head<3>() = p;
  const Matrix<5, 3> h = sensor.jacobian(x).leftCols<3>();
  SmallCholesky<3> information;
  ASSERT_TRUE(information.compute(h.transpose() * h / (sigma * sigma)));
  const Covariance<3> covariance = information.inverse();

  std::mt19937 rng(55);
  std::normal_distribution<double> unit;
  constexpr int kDraws = 2000;
  double nees = 0.0;
  for (int draw = 0; draw < kDraws; ++draw) {
    Vector<5> z = sensor.measure_position(p);
    for (int i = 0; i < 5; ++i) z(i) += sigma * unit(rng);
    const Vector3 e = sensor.position_of(z) - p;
    nees += e.dot(covariance.ldlt().solve(e));
  }
  const ChiSquareBand band = average_chi_square_band(3, kDraws, 0.99);
  EXPECT_GE(nees / kDraws, band.lower);
  EXPECT_LE(nees / kDraws, band.upper);
}

TEST(Multilateration, RefusesWhatNoGroupReports) {
  EXPECT_EQ(Sensor::check_reported(Vector<5>(1.0, -2.0, 3.0, 0.0, 5.0)), std::nullopt);
  EXPECT_EQ(Sensor::check_reported(Vector<5>(1.0, -2e6, 3.0, 0.0, 5.0)), DropKind::kOutOfRange);
  EXPECT_EQ(Sensor::check_reported(Vector<5>(1.0, 2.0, std::nan(""), 0.0, 5.0)),
            DropKind::kNonFinite);
}

}  // namespace
}  // namespace skyfuse
