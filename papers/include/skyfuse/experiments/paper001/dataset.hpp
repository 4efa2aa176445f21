#pragma once
/// \file
/// Paper 001's data set: paths split 7:2:1 by path (no window of a test path is ever trained
/// on), each tracked by the CVKF, cut into 14-step windows of 6 features for the two networks.
///
/// A window's features at each step: the CVKF posterior [x, vx, y, vy] and the measurement
/// [x, y]. Its target, at the window's last step: the CVKF's position error p_true - p_CVKF for
/// error compensation (EC), the true position for state estimation (SE).
///
/// The positions (x, y of the posterior and the measurement) come in one of two frames: as
/// they are (absolute), or relative to the CVKF position at the window's last step. The paper
/// does not say how it scaled its inputs; in absolute coordinates, z-scored, a 3 m innovation
/// is 0.014 of a feature's spread (the positions spread over ~210 m), and the EC network
/// learns from it slowly (docs/paper001.md).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/experiments/paper001/manoeuvring_path.hpp"

namespace skyfuse::paper001 {

inline constexpr int kWindowSteps = 14;
inline constexpr int kWindowFeatures = 6;

enum class Split { kTrain, kValidation, kTest };
enum class Network { kErrorCompensation, kStateEstimation };
enum class WindowFrame { kAbsolute, kRelative };

/// The frame a network's weights file names ("absolute" or "relative"); throws
/// std::invalid_argument on anything else.
WindowFrame window_frame_named(const std::string& name);
const char* name_of(WindowFrame frame);

struct DataSetup {
  PathSetup path;
  int paths = 10000;
  std::uint64_t seed = 1;
  /// sigma_Q^2 of every filter (eq 14)
  double process_variance = 10.0;
  /// The filters start at the true initial state with P0 = I (SEEDS.md default).
  double initial_variance = 1.0;
};

/// One path with the CVKF run over it.
struct TrackedPath {
  ManoeuvringPath path;
  /// CVKF posterior [x, vx, y, vy] at each step.
  std::vector<Vector<4>> cvkf;
};

/// Paths [0, 0.7 n) train, [0.7 n, 0.9 n) validate, [0.9 n, n) test.
Split split_of(const DataSetup& setup, int path_index);
/// The indices of the paths in `split`, in order.
std::vector<int> paths_in(const DataSetup& setup, Split split);

TrackedPath track_path(const DataSetup& setup, int path_index);

/// The features of the window ending at step `last` (>= kWindowSteps - 1) of a tracked path,
/// row-major kWindowSteps x kWindowFeatures, unscaled, positions in `frame`.
Matrix<kWindowSteps, kWindowFeatures> window_features(const TrackedPath& tracked, int last,
                                                      WindowFrame frame);
/// The target of that window for `network`.
Vector<2> window_target(const TrackedPath& tracked, int last, Network network);

/// Every window of every path of a split, windows starting every `stride` steps, as float
/// arrays: inputs count x kWindowSteps x kWindowFeatures (row-major), targets count x 2.
struct Windows {
  std::vector<float> inputs;
  std::vector<float> targets;
  std::size_t count() const { return targets.size() / 2; }
};
Windows make_windows(const DataSetup& setup, Split split, Network network, int stride,
                     WindowFrame frame);

}  // namespace skyfuse::paper001
