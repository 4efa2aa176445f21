// Fuzz target: check_observation on a measurement made of arbitrary doubles. It must never
// crash, and a measurement it accepts must be one the center can fuse: z, R and the station
// position finite, R symmetric and positive definite, z within what the sensor reports.
//
// Input (see fuzz_input.hpp): z (3 doubles), R's upper triangle (6), the station position (3).
// The station id is not read by the check, so it is not fuzzed.

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "fuzz_input.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace {

using Sensor = skyfuse::RangeAzimuthElevation<9>;
using Observation = skyfuse::StationObservation<Sensor>;

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "observation_check_fuzz: accepted a measurement that %s\n", what);
  std::abort();
}

Observation decode(skyfuse::fuzz::FuzzInput& in) {
  Observation o;
  o.z = in.vector<3>();
  o.noise = in.symmetric<3>();
  o.sensor = Sensor(in.vector<3>());
  return o;
}

// R positive definite by Eigen's Cholesky rather than the check's own small one. The two round
// differently, so on a matrix singular to within rounding (a rank-1 R, say) either may pass
// it; only a clearly negative eigenvalue, beyond 1e-12 of the largest, makes a finding.
void verify_positive_definite(const skyfuse::Covariance<3>& r) {
  if (Eigen::LLT<skyfuse::Covariance<3>>(r).info() == Eigen::Success) return;
  // Scaled to a largest entry of 1, so that no eigenvalue overflows.
  const Eigen::SelfAdjointEigenSolver<skyfuse::Covariance<3>> eigen(r / r.cwiseAbs().maxCoeff(),
                                                                    Eigen::EigenvaluesOnly);
  const auto eigenvalues = eigen.eigenvalues();
  if (eigenvalues.minCoeff() < -1e-12 * eigenvalues.cwiseAbs().maxCoeff()) {
    finding("has an R that is not positive definite");
  }
}

void verify_accepted(const Observation& o) {
  if (!o.z.allFinite() || !o.noise.allFinite() || !o.sensor.station_position().allFinite()) {
    finding("is not finite");
  }
  if (o.noise != o.noise.transpose()) finding("has an R that is not symmetric");
  verify_positive_definite(o.noise);
  constexpr double kPi = std::numbers::pi;
  const double range = o.z(Sensor::kRange);
  if (!(range > 0.0 && range <= skyfuse::kMaxRangeM)) finding("has a range out of (0, 1000 km]");
  if (!(std::abs(o.z(Sensor::kAzimuth)) <= kPi)) finding("has an azimuth out of [-pi, pi]");
  if (!(std::abs(o.z(Sensor::kElevation)) <= kPi / 2.0)) {
    finding("has an elevation out of [-pi/2, pi/2]");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  skyfuse::fuzz::FuzzInput in(data, size);
  const Observation observation = decode(in);
  if (skyfuse::check_observation(observation) == std::nullopt) verify_accepted(observation);
  return 0;
}
