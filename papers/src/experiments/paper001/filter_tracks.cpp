#include "skyfuse/experiments/paper001/filter_tracks.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "skyfuse/filters/imm.hpp"
#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/learning/lstm_network.hpp"
#include "skyfuse/models/planar/constant_acceleration_2d.hpp"
#include "skyfuse/models/planar/constant_velocity_2d.hpp"
#include "skyfuse/models/planar/coordinated_turn_2d.hpp"
#include "skyfuse/models/planar/position_2d.hpp"

namespace skyfuse::paper001 {
namespace {

// A filter that fails a step has no estimate to report: the run stops, naming the step.
void require_ok(NumericalStatus status, const char* filter, std::size_t step) {
  if (status != NumericalStatus::kOk) {
    throw std::runtime_error(
        fmt::format("paper 001: the {} failed at step {}: {}", filter, step, to_string(status)));
  }
}

Covariance<2> measurement_noise(const DataSetup& setup) {
  return setup.path.measurement_std_m * setup.path.measurement_std_m * Covariance<2>::Identity();
}

}  // namespace

PositionTrack cvkf_track(const TrackedPath& tracked) {
  PositionTrack out;
  out.reserve(tracked.cvkf.size());
  for (const Vector<4>& x : tracked.cvkf) out.emplace_back(x(0), x(2));
  return out;
}

PositionTrack ekf_track(const DataSetup& setup, const TrackedPath& tracked, TurnRateNoise noise) {
  const TurnRateVelocity2D model(setup.path.time_step_s, setup.process_variance, noise);
  const Covariance<2> r = measurement_noise(setup);
  GaussianState<5> state{tracked.path.truth.front(),
                         setup.initial_variance * Covariance<5>::Identity()};
  PositionTrack out{state.mean.head<2>()};
  for (std::size_t k = 1; k < tracked.path.truth.size(); ++k) {
    predict(state, model);
    require_ok(
        update(state, Position2D<TurnRateVelocity2D>{}, tracked.path.measurements[k], r).status,
        "EKF", k);
    out.emplace_back(state.mean.head<2>());
  }
  return out;
}

PositionTrack imm_track(const DataSetup& setup, const TrackedPath& tracked) {
  using PlanarImm = Imm<PlanarState, ConstantVelocity2D, ConstantAcceleration2D, CoordinatedTurn2D>;
  const double dt = setup.path.time_step_s;
  const double q = setup.process_variance;
  // SEEDS.md defaults where the paper is silent: p_ii = 0.95, p_ij = 0.025, mu_0 = 1/3 each.
  Matrix<3, 3> switching = Matrix<3, 3>::Constant(0.025);
  switching.diagonal().setConstant(0.95);

  const Vector<5>& start = tracked.path.truth.front();
  PlanarImm::CommonState initial;
  initial.mean << cartesian_position_velocity(start), 0.0, 0.0, start(4);
  initial.covariance = setup.initial_variance * Covariance<PlanarState::kDim>::Identity();
  PlanarImm imm(
      {ConstantVelocity2D(dt, q), ConstantAcceleration2D(dt, q), CoordinatedTurn2D(dt, q)},
      switching, Vector<3>::Constant(1.0 / 3.0), initial);

  const Covariance<2> r = measurement_noise(setup);
  PositionTrack out{Vector<2>(start(0), start(1))};
  for (std::size_t k = 1; k < tracked.path.truth.size(); ++k) {
    imm.predict();
    require_ok(imm.update<Position2D>(tracked.path.measurements[k], r), "IMM", k);
    const PlanarImm::CommonState estimate = imm.estimate();
    out.emplace_back(estimate.mean(PlanarState::kX), estimate.mean(PlanarState::kY));
  }
  return out;
}

PositionTrack network_track(const TrackedPath& tracked, learning::LstmNetwork& network,
                            Network kind) {
  const WindowFrame frame = window_frame_named(network.record().frame);
  if (kind == Network::kStateEstimation && frame == WindowFrame::kRelative) {
    throw std::invalid_argument("paper 001: a state-estimation network needs absolute positions");
  }
  PositionTrack out = cvkf_track(tracked);
  for (int last = kWindowSteps - 1; last < static_cast<int>(out.size()); ++last) {
    const Vector<2> prediction = network.predict(window_features(tracked, last, frame));
    const auto k = static_cast<std::size_t>(last);
    out[k] = kind == Network::kErrorCompensation ? Vector<2>(out[k] + prediction) : prediction;
  }
  return out;
}

double path_rmse(const TrackedPath& tracked, const PositionTrack& track) {
  if (track.size() != tracked.path.truth.size() || track.size() < 2) {
    throw std::invalid_argument("paper 001: a track must have one position per step of its path");
  }
  double sum = 0.0;
  for (std::size_t k = 1; k < track.size(); ++k) {
    sum += (track[k] - tracked.path.truth[k].head<2>()).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(track.size() - 1));
}

double per_axis_rmse(const TrackedPath& tracked, const PositionTrack& track) {
  return path_rmse(tracked, track) / std::numbers::sqrt2;
}

}  // namespace skyfuse::paper001
