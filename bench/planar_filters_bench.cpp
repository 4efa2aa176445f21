// Paper 001's filters, one predict + update step each on a turning target: the CVKF, the CA
// and CT modes alone, the CTRV EKF, and the IMM of CV + CA + CT, whose cost is to be read
// against the sum of its three modes'.

#include <benchmark/benchmark.h>

#include <cmath>

#include "skyfuse/filters/imm.hpp"
#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/models/planar/constant_acceleration_2d.hpp"
#include "skyfuse/models/planar/constant_velocity_2d.hpp"
#include "skyfuse/models/planar/coordinated_turn_2d.hpp"
#include "skyfuse/models/planar/position_2d.hpp"
#include "skyfuse/models/planar/turn_rate_velocity_2d.hpp"

namespace skyfuse {
namespace {

constexpr double kDt = 0.1;
constexpr double kSigmaQ2 = 10.0;
const Covariance<2> kR = 9.0 * Covariance<2>::Identity();

// A target on a 0.3 rad/s turn at 20 m/s, measured without noise: the filters' arithmetic does
// not depend on the values, and a settled track keeps every step alike.
Vector<2> measurement(int k) {
  const double angle = 0.3 * kDt * k;
  return {66.7 * std::sin(angle), 66.7 * (1.0 - std::cos(angle))};
}

template <typename Model>
void single_model_step(benchmark::State& bench, const Model& model, Vector<Model::kDim> start) {
  GaussianState<Model::kDim> state{start, Covariance<Model::kDim>::Identity()};
  int k = 0;
  for (auto _ : bench) {
    predict(state, model);
    benchmark::DoNotOptimize(update(state, Position2D<Model>{}, measurement(++k), kR));
    if (k == 1000) {  // restart before the turn wraps around
      k = 0;
      state = {start, Covariance<Model::kDim>::Identity()};
    }
  }
}

void CvkfStep(benchmark::State& bench) {
  single_model_step(bench, ConstantVelocity2D(kDt, kSigmaQ2), Vector<4>(0.0, 20.0, 0.0, 0.0));
}
BENCHMARK(CvkfStep);

void Ca2dStep(benchmark::State& bench) {
  Vector<6> start = Vector<6>::Zero();
  start(1) = 20.0;
  single_model_step(bench, ConstantAcceleration2D(kDt, kSigmaQ2), start);
}
BENCHMARK(Ca2dStep);

void Ct2dEkfStep(benchmark::State& bench) {
  Vector<5> start;
  start << 0.0, 20.0, 0.0, 0.0, 0.3;
  single_model_step(bench, CoordinatedTurn2D(kDt, kSigmaQ2), start);
}
BENCHMARK(Ct2dEkfStep);

void CtrvEkfStep(benchmark::State& bench) {
  Vector<5> start;
  start << 0.0, 0.0, 0.0, 20.0, 0.3;
  single_model_step(bench, TurnRateVelocity2D(kDt, kSigmaQ2), start);
}
BENCHMARK(CtrvEkfStep);

void ImmStep(benchmark::State& bench) {
  using PlanarImm = Imm<PlanarState, ConstantVelocity2D, ConstantAcceleration2D, CoordinatedTurn2D>;
  Matrix<3, 3> switching = Matrix<3, 3>::Constant(0.025);
  switching.diagonal().setConstant(0.95);
  PlanarImm::CommonState start;
  start.mean << 0.0, 20.0, 0.0, 0.0, 0.0, 0.0, 0.3;
  const auto fresh = [&] {
    return PlanarImm({ConstantVelocity2D(kDt, kSigmaQ2), ConstantAcceleration2D(kDt, kSigmaQ2),
                      CoordinatedTurn2D(kDt, kSigmaQ2)},
                     switching, Vector<3>::Constant(1.0 / 3.0), start);
  };
  PlanarImm imm = fresh();
  int k = 0;
  for (auto _ : bench) {
    imm.predict();
    benchmark::DoNotOptimize(imm.update<Position2D>(measurement(++k), kR));
    benchmark::DoNotOptimize(imm.estimate());
    if (k == 1000) {
      k = 0;
      imm = fresh();
    }
  }
}
BENCHMARK(ImmStep);

}  // namespace
}  // namespace skyfuse
