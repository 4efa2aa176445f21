#include "skyfuse/experiments/paper003.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/random/counter_rng.hpp"

namespace skyfuse {
namespace {

using Model = ConstantVelocity3D;
using Gps = PositionVelocity<Model::kDim>;

// A draw from N(0, C) for a diagonal C.
Vector<6> draw_diagonal(CounterRng& rng, const Covariance<6>& c) {
  Vector<6> out;
  for (int i = 0; i < 6; ++i) out(i) = std::sqrt(c(i, i)) * rng.normal();
  return out;
}

// Iterates P- = F P+ F^T + Q, P+ = (I - K H) P- until P+ stops changing.
Covariance<6> riccati_fixed_point(const Model& model, const Covariance<6>& r, Covariance<6> p) {
  const Gps gps;
  for (int i = 0; i < 10000; ++i) {
    GaussianState<6> state{Vector<6>::Zero(), p};
    predict(state, model);
    update(state, gps, Vector<6>::Zero(), r);
    const double change = (state.covariance - p).cwiseAbs().maxCoeff();
    p = state.covariance;
    if (change <= 1e-13 * p.cwiseAbs().maxCoeff()) break;
  }
  return p;
}

}  // namespace

Paper003Result run_paper003(const Paper003Setup& setup) {
  if (setup.steps < 1 || setup.runs < 1 || !(setup.time_step_s > 0.0)) {
    throw std::invalid_argument("paper 003: steps and runs must be >= 1 and dt > 0");
  }
  const Model model(setup.time_step_s,
                    {setup.process_position_std_m, setup.process_velocity_std_mps});
  Vector<6> r_diagonal;
  r_diagonal << Vector3::Constant(setup.gps_position_std_m * setup.gps_position_std_m),
      Vector3::Constant(setup.gps_velocity_std_mps * setup.gps_velocity_std_mps);
  const Covariance<6> r = r_diagonal.asDiagonal();
  const Gps gps;

  const auto steps = static_cast<std::size_t>(setup.steps);
  Paper003Result result;
  result.mse_position.assign(steps, Vector3::Zero());
  result.mse_velocity.assign(steps, Vector3::Zero());
  for (std::size_t k = 0; k < steps; ++k) {
    result.time_s.push_back(static_cast<double>(k + 1) * setup.time_step_s);
  }

  for (int run = 0; run < setup.runs; ++run) {
    const auto run_key = static_cast<std::uint64_t>(run);
    Vector<6> truth = setup.true_start;
    GaussianState<6> estimate{Vector<6>::Zero(),
                              setup.initial_variance * Covariance<6>::Identity()};
    for (std::size_t k = 0; k < steps; ++k) {
      CounterRng process_rng({setup.seed, run_key, 0, k + 1, NoiseStream::kProcess});
      truth = model.propagate(truth) + draw_diagonal(process_rng, model.process_noise());
      CounterRng gps_rng({setup.seed, run_key, 1, k + 1, NoiseStream::kMeasurement});
      const Vector<6> z = gps.predict(truth) + draw_diagonal(gps_rng, r);

      predict(estimate, model);
      if (update(estimate, gps, z, r).status != NumericalStatus::kOk) {
        throw std::runtime_error("paper 003: the update failed");  // R > 0: cannot happen
      }
      const Vector<6> error = truth - estimate.mean;
      result.mse_position[k] += error.head<3>().cwiseAbs2();
      result.mse_velocity[k] += error.tail<3>().cwiseAbs2();
      if (run == 0) {
        result.example_truth.push_back(truth);
        result.example_estimate.push_back(estimate.mean);
      }
    }
  }
  for (std::size_t k = 0; k < steps; ++k) {
    result.mse_position[k] /= setup.runs;
    result.mse_velocity[k] /= setup.runs;
  }
  result.steady_state_posterior =
      riccati_fixed_point(model, r, setup.initial_variance * Covariance<6>::Identity());
  return result;
}

}  // namespace skyfuse
