#pragma once
/// \file
/// Each of paper 001's filters run over one tracked path, as the position it reports at every
/// step. All start at the true initial state with P0 = I and use sigma_Q^2 = 10, R = 9 I
/// (eq 14); step 0 reports that initial state.

#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/experiments/paper001/dataset.hpp"
#include "skyfuse/models/planar/turn_rate_velocity_2d.hpp"

namespace skyfuse::learning {
class LstmNetwork;
}

namespace skyfuse::paper001 {

using PositionTrack = std::vector<Vector<2>>;

/// The CVKF's own positions (already in the tracked path).
PositionTrack cvkf_track(const TrackedPath& tracked);
/// The EKF on [x, y, theta, v, omega] (eq 15-17) with the given process noise.
PositionTrack ekf_track(const DataSetup& setup, const TrackedPath& tracked, TurnRateNoise noise);
/// The IMM of CV, CA and CT (p_ii = 0.95, mu_0 = 1/3 each): the mixture's position.
PositionTrack imm_track(const DataSetup& setup, const TrackedPath& tracked);
/// The CVKF corrected by the error-compensation network (EC), or the state-estimation
/// network's positions (SE): `network` predicts at each step from the window ending there;
/// before the first full window (k < 13) the CVKF's own position stands. The windows are built
/// in the frame the network's weights name; a state-estimation network in the relative frame
/// is refused (std::invalid_argument): it could not know where the target is.
PositionTrack network_track(const TrackedPath& tracked, learning::LstmNetwork& network,
                            Network kind);

/// sqrt(mean over steps 1..L-1 of |p_hat - p|^2): the 2-D (Euclidean) per-path RMSE.
double path_rmse(const TrackedPath& tracked, const PositionTrack& track);
/// sqrt(mean over steps 1..L-1 and both axes of (p_hat - p)^2) = path_rmse / sqrt(2): the
/// per-path RMSE of the paper's Tables 2-4. Its IMM (1.48 m) lies below what a 2-D RMSE can be
/// for a filter whose every mode is at least as noisy as the CVKF: the CVKF's steady state
/// alone is sqrt(2 x 1.216) = 1.56 m in 2-D on a straight line (SEEDS.md).
double per_axis_rmse(const TrackedPath& tracked, const PositionTrack& track);

}  // namespace skyfuse::paper001
