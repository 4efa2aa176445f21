#include "skyfuse/experiments/paper002.hpp"

#include <cmath>
#include <stdexcept>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/filters/ncrkf.hpp"
#include "skyfuse/models/tdoa/block_constant_acceleration.hpp"
#include "skyfuse/models/tdoa/pseudo_linear_tdoa.hpp"
#include "skyfuse/models/tdoa/range_difference_sensor.hpp"
#include "skyfuse/models/tdoa/tdoa_relative_motion.hpp"
#include "skyfuse/random/counter_rng.hpp"

namespace skyfuse {
namespace {

using PseudoLinearModel = BlockConstantAcceleration<3>;  // [dx, dy, d_t1, ...]
using EkfModel = BlockConstantAcceleration<2>;           // [dx, dy, ...]
constexpr int kFilters = 4;
// Receivers are numbered from 2 (UAV 1 is the reference); the key of their noise streams.
constexpr std::uint64_t kFirstReceiver = 2;

// The relative kinematics (target minus UAV 1) at time t: constant velocities.
struct Relative {
  Vector<2> position;
  Vector<2> velocity;
};

Relative relative_at(const Paper002Setup& s, double t) {
  const Vector<2> start =
      s.target_range_m * Vector<2>(std::cos(s.target_bearing_rad), std::sin(s.target_bearing_rad));
  const Vector<2> velocity = s.target_velocity_mps - s.formation_velocity_mps;
  return {start + velocity * t, velocity};
}

struct Accumulator {
  std::vector<double> sum_x, sum_sq_x, sum_vx, sum_sq_vx;
  explicit Accumulator(std::size_t n) : sum_x(n), sum_sq_x(n), sum_vx(n), sum_sq_vx(n) {}
  void add(std::size_t k, double error_x, double error_vx) {
    sum_x[k] += error_x;
    sum_sq_x[k] += error_x * error_x;
    sum_vx[k] += error_vx;
    sum_sq_vx[k] += error_vx * error_vx;
  }
  ErrorSeries series(int runs) const {
    ErrorSeries out;
    for (std::size_t k = 0; k < sum_x.size(); ++k) {
      out.mean_error_x_m.push_back(sum_x[k] / runs);
      out.rmse_x_m.push_back(std::sqrt(sum_sq_x[k] / runs));
      out.mean_error_vx_mps.push_back(sum_vx[k] / runs);
      out.rmse_vx_mps.push_back(std::sqrt(sum_sq_vx[k] / runs));
    }
    return out;
  }
};

void check(const Paper002Setup& s) {
  if (s.steps < 1 || s.runs < 1 || s.receiver_offsets_m.empty() || !(s.time_step_s > 0.0) ||
      !(s.range_difference_std_m > 0.0) || !(s.process_noise > 0.0)) {
    throw std::invalid_argument(
        "paper 002: steps, runs and receivers must be >= 1; the time step, the range-difference "
        "noise and the process noise > 0");
  }
}

}  // namespace

Paper002Result run_paper002(const Paper002Setup& s) {
  check(s);
  const auto steps = static_cast<std::size_t>(s.steps) + 1;  // step 0: the initial estimates
  const PseudoLinearModel pseudo_linear_model(s.time_step_s, s.process_noise);
  const EkfModel ekf_model(s.time_step_s, s.process_noise);
  const double sigma = s.range_difference_std_m;
  const Covariance<1> ekf_noise = Covariance<1>::Constant(sigma * sigma);
  std::vector<RangeDifferenceSensor<6>> receivers;
  for (const Vector<2>& offset : s.receiver_offsets_m) receivers.emplace_back(offset);

  Covariance<9> p0 = Covariance<9>::Zero();
  for (int block = 0; block < 3; ++block) {
    p0.diagonal().segment<3>(3 * block).setConstant(s.initial_variance(block));
  }
  Covariance<6> p0_ekf = Covariance<6>::Zero();
  for (int block = 0; block < 3; ++block) {
    p0_ekf.diagonal().segment<2>(2 * block).setConstant(s.initial_variance(block));
  }

  std::vector<Accumulator> errors(kFilters, Accumulator(steps));
  Paper002Result out;
  std::vector<PseudoLinearTdoaRow> measured_rows(receivers.size());
  std::vector<PseudoLinearTdoaRow> true_rows(receivers.size());
  std::vector<double> measured(receivers.size());
  TdoaUpdateScratch scratch;

  for (int r = 0; r < s.runs; ++r) {
    const auto run = static_cast<std::uint64_t>(r);
    // The initial estimate: the truth plus N(0, 300^2) on position and N(0, 10^2) on velocity;
    // d and d' follow from them, the accelerations start at 0.
    const Relative start = relative_at(s, 0.0);
    CounterRng start_noise({s.seed, run, 0, 0, NoiseStream::kInitialState});
    Vector<2> p_hat = start.position;
    Vector<2> v_hat = start.velocity;
    for (int i = 0; i < 2; ++i) p_hat(i) += s.initial_position_std_m * start_noise.normal();
    for (int i = 0; i < 2; ++i) v_hat(i) += s.initial_velocity_std_mps * start_noise.normal();
    Vector<9> kinematics = Vector<9>::Zero();
    kinematics << p_hat, 0.0, v_hat, 0.0, 0.0, 0.0, 0.0;
    Vector<9> x0 = TdoaRelativeMotion::from_kinematics(kinematics);
    x0.tail<3>().setZero();  // the accelerations, d'' included, start at 0
    std::array<GaussianState<9>, 3> linear{GaussianState<9>{x0, p0}, GaussianState<9>{x0, p0},
                                           GaussianState<9>{x0, p0}};
    Vector<6> x0_ekf = Vector<6>::Zero();
    x0_ekf << p_hat, v_hat, 0.0, 0.0;
    GaussianState<6> ekf{x0_ekf, p0_ekf};

    for (std::size_t k = 0; k < steps; ++k) {
      const Relative truth = relative_at(s, static_cast<double>(k) * s.time_step_s);
      if (k > 0) {
        for (GaussianState<9>& state : linear) predict(state, pseudo_linear_model);
        predict(ekf, ekf_model);
        for (std::size_t j = 0; j < receivers.size(); ++j) {
          CounterRng noise({s.seed, run, kFirstReceiver + j, k, NoiseStream::kMeasurement});
          const double r_true = range_difference(truth.position, s.receiver_offsets_m[j]);
          measured[j] = r_true + sigma * noise.normal();
          measured_rows[j] =
              pseudo_linear_tdoa_row(s.receiver_offsets_m[j], measured[j], measured[j], sigma);
          true_rows[j] =
              pseudo_linear_tdoa_row(s.receiver_offsets_m[j], measured[j], r_true, sigma);
        }
        const std::array<std::pair<const std::vector<PseudoLinearTdoaRow>*, BiasCompensation>, 3>
            updates = {{{&measured_rows, BiasCompensation::kCompensated},
                        {&measured_rows, BiasCompensation::kNone},
                        {&true_rows, BiasCompensation::kNone}}};
        for (std::size_t f = 0; f < updates.size(); ++f) {
          if (tdoa_update(linear[f], *updates[f].first, updates[f].second, scratch) !=
              NumericalStatus::kOk) {
            ++out.not_positive_definite[f];
          }
        }
        for (std::size_t j = 0; j < receivers.size(); ++j) {
          if (update(ekf, receivers[j], Vector<1>(measured[j]), ekf_noise).status !=
              NumericalStatus::kOk) {
            ++out.not_positive_definite[static_cast<std::size_t>(Paper002Filter::kEkf)];
          }
        }
      }
      for (std::size_t f = 0; f < linear.size(); ++f) {
        errors[f].add(k, linear[f].mean(0) - truth.position.x(),
                      linear[f].mean(3) - truth.velocity.x());
      }
      errors[3].add(k, ekf.mean(0) - truth.position.x(), ekf.mean(2) - truth.velocity.x());
    }
  }

  for (std::size_t k = 0; k < steps; ++k)
    out.time_s.push_back(static_cast<double>(k) * s.time_step_s);
  for (int f = 0; f < kFilters; ++f) {
    out.filters[static_cast<std::size_t>(f)] = errors[static_cast<std::size_t>(f)].series(s.runs);
  }
  out.initial_range_m = relative_at(s, 0.0).position.norm();
  out.final_range_m = relative_at(s, out.time_s.back()).position.norm();
  return out;
}

}  // namespace skyfuse
