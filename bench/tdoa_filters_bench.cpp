// Paper 002's filters, one predict + update step each with three receivers' range differences:
// the NCRKF, the nominal KF (the same update without W and V; the optimal KF costs the same),
// and the EKF on the range differences.

#include <benchmark/benchmark.h>

#include <vector>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/filters/ncrkf.hpp"
#include "skyfuse/models/tdoa/block_constant_acceleration.hpp"
#include "skyfuse/models/tdoa/range_difference_sensor.hpp"

namespace skyfuse {
namespace {

constexpr double kT = 0.002;
constexpr double kSigma = 0.4;
const std::vector<Vector<2>> kOffsets = {Vector<2>(200.0, 0.0), Vector<2>(-200.0, 0.0),
                                         Vector<2>(0.0, 200.0)};
// A target 3 km out; the values do not change the arithmetic.
const Vector<2> kTarget(1864.9, 2350.0);

void pseudo_linear_step(benchmark::State& bench, BiasCompensation compensation) {
  const BlockConstantAcceleration<3> model(kT, 0.01);
  Vector<9> start = Vector<9>::Zero();
  start << kTarget, kTarget.norm(), -45.0, 10.0, 0.0, 0.0, 0.0, 0.0;
  GaussianState<9> state{start, Covariance<9>::Identity() * 100.0};
  std::vector<PseudoLinearTdoaRow> rows(kOffsets.size());
  TdoaUpdateScratch scratch;
  for (auto _ : bench) {
    predict(state, model);
    for (std::size_t j = 0; j < kOffsets.size(); ++j) {
      const double r = range_difference(kTarget, kOffsets[j]);
      rows[j] = pseudo_linear_tdoa_row(kOffsets[j], r, r, kSigma);
    }
    benchmark::DoNotOptimize(tdoa_update(state, rows, compensation, scratch));
  }
}

void NcrkfStep(benchmark::State& bench) {
  pseudo_linear_step(bench, BiasCompensation::kCompensated);
}
BENCHMARK(NcrkfStep);

void NominalKfStep(benchmark::State& bench) {
  pseudo_linear_step(bench, BiasCompensation::kNone);
}
BENCHMARK(NominalKfStep);

void TdoaEkfStep(benchmark::State& bench) {
  const BlockConstantAcceleration<2> model(kT, 0.01);
  std::vector<RangeDifferenceSensor<6>> receivers;
  for (const Vector<2>& offset : kOffsets) receivers.emplace_back(offset);
  Vector<6> start = Vector<6>::Zero();
  start << kTarget, -45.0, 10.0, 0.0, 0.0;
  GaussianState<6> state{start, Covariance<6>::Identity() * 100.0};
  const Covariance<1> noise = Covariance<1>::Constant(kSigma * kSigma);
  for (auto _ : bench) {
    predict(state, model);
    for (const auto& receiver : receivers) {
      benchmark::DoNotOptimize(
          update(state, receiver, Vector<1>(range_difference(kTarget, receiver.offset())), noise));
    }
  }
}
BENCHMARK(TdoaEkfStep);

}  // namespace
}  // namespace skyfuse
