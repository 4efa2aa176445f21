#include "skyfuse/experiments/paper001/dataset.hpp"

#include <cmath>
#include <stdexcept>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/models/planar/constant_velocity_2d.hpp"
#include "skyfuse/models/planar/position_2d.hpp"

namespace skyfuse::paper001 {

Split split_of(const DataSetup& setup, int path_index) {
  if (path_index < 0 || path_index >= setup.paths) {
    throw std::out_of_range("paper 001: path index outside the data set");
  }
  // Integer arithmetic: 7:2:1 of 10 000 is exactly 7000 / 2000 / 1000.
  const long scaled = 10L * path_index;
  if (scaled < 7L * setup.paths) return Split::kTrain;
  if (scaled < 9L * setup.paths) return Split::kValidation;
  return Split::kTest;
}

std::vector<int> paths_in(const DataSetup& setup, Split split) {
  std::vector<int> out;
  for (int i = 0; i < setup.paths; ++i) {
    if (split_of(setup, i) == split) out.push_back(i);
  }
  return out;
}

TrackedPath track_path(const DataSetup& setup, int path_index) {
  TrackedPath tracked{generate_path(setup.path, setup.seed, static_cast<std::uint64_t>(path_index)),
                      {}};
  const ConstantVelocity2D model(setup.path.time_step_s, setup.process_variance);
  const Position2D<ConstantVelocity2D> sensor;
  const double r = setup.path.measurement_std_m * setup.path.measurement_std_m;
  const Covariance<2> noise = r * Covariance<2>::Identity();

  const Vector<5>& start = tracked.path.truth.front();
  GaussianState<4> state;
  state.mean = cartesian_position_velocity(start);
  state.covariance = setup.initial_variance * Covariance<4>::Identity();
  tracked.cvkf.reserve(tracked.path.truth.size());
  tracked.cvkf.push_back(state.mean);
  for (std::size_t k = 1; k < tracked.path.truth.size(); ++k) {
    predict(state, model);
    update(state, sensor, tracked.path.measurements[k], noise);
    tracked.cvkf.push_back(state.mean);
  }
  return tracked;
}

WindowFrame window_frame_named(const std::string& name) {
  if (name == "absolute") return WindowFrame::kAbsolute;
  if (name == "relative") return WindowFrame::kRelative;
  throw std::invalid_argument("paper 001: unknown window frame '" + name +
                              "' (expected absolute or relative)");
}

const char* name_of(WindowFrame frame) {
  return frame == WindowFrame::kAbsolute ? "absolute" : "relative";
}

Matrix<kWindowSteps, kWindowFeatures> window_features(const TrackedPath& tracked, int last,
                                                      WindowFrame frame) {
  if (last < kWindowSteps - 1 || last >= static_cast<int>(tracked.cvkf.size())) {
    throw std::out_of_range("paper 001: a window must end inside the path, after 13 steps");
  }
  Matrix<kWindowSteps, kWindowFeatures> features;
  for (int row = 0; row < kWindowSteps; ++row) {
    const auto k = static_cast<std::size_t>(last - (kWindowSteps - 1) + row);
    features.row(row) << tracked.cvkf[k].transpose(), tracked.path.measurements[k].transpose();
  }
  if (frame == WindowFrame::kRelative) {
    const Vector<4>& origin = tracked.cvkf[static_cast<std::size_t>(last)];
    for (const int column : {0, 4}) features.col(column).array() -= origin(0);  // x
    for (const int column : {2, 5}) features.col(column).array() -= origin(2);  // y
  }
  return features;
}

Vector<2> window_target(const TrackedPath& tracked, int last, Network network) {
  const auto k = static_cast<std::size_t>(last);
  const Vector<2> truth = tracked.path.truth[k].head<2>();
  if (network == Network::kStateEstimation) return truth;
  return truth - Vector<2>(tracked.cvkf[k](0), tracked.cvkf[k](2));
}

Windows make_windows(const DataSetup& setup, Split split, Network network, int stride,
                     WindowFrame frame) {
  if (stride < 1) throw std::invalid_argument("paper 001: the window stride must be >= 1");
  Windows out;
  for (const int index : paths_in(setup, split)) {
    const TrackedPath tracked = track_path(setup, index);
    const int steps = static_cast<int>(tracked.cvkf.size());
    for (int last = kWindowSteps - 1; last < steps; last += stride) {
      const Matrix<kWindowSteps, kWindowFeatures> features = window_features(tracked, last, frame);
      for (int row = 0; row < kWindowSteps; ++row) {
        for (int col = 0; col < kWindowFeatures; ++col) {
          out.inputs.push_back(static_cast<float>(features(row, col)));
        }
      }
      const Vector<2> target = window_target(tracked, last, network);
      out.targets.push_back(static_cast<float>(target(0)));
      out.targets.push_back(static_cast<float>(target(1)));
    }
  }
  return out;
}

}  // namespace skyfuse::paper001
