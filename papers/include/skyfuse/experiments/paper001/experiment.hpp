#pragma once
/// \file
/// Paper 001's Monte Carlo: every filter over the test paths (Table 3), the paths that stay in
/// the training range (Table 4), the networks' training targets (Table 1), and longer paths
/// that leave the training range, where the state-estimation network has nothing to go on.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/experiments/paper001/dataset.hpp"
#include "skyfuse/experiments/paper001/filter_tracks.hpp"
#include "skyfuse/learning/lstm_weights.hpp"

namespace skyfuse::paper001 {

struct ExperimentSetup {
  DataSetup data;
  /// How many of the test split's paths to run; 0 = all of them (1000 of 10 000).
  int test_paths = 0;
  /// Table 1's windows start every `table1_stride` steps (the paper's "skip 3 points").
  int table1_stride = 3;
  /// Table 4: test paths whose truth stays within +-range_m on both axes, the first `count`.
  double in_range_m = 210.0;
  int in_range_paths = 100;
  /// Paths `beyond_range_length` times as long, drawn from another seed, that carry the
  /// target far past where any training path went.
  int beyond_range_paths = 100;
  int beyond_range_length = 3;
  /// The trained networks; without them only the filters run.
  std::optional<std::filesystem::path> ec_weights;
  std::optional<std::filesystem::path> se_weights;
  /// Optionally a second EC network, trained on absolute positions like SE, scored beside the
  /// first as "EC (absolute frame)".
  std::optional<std::filesystem::path> ec_absolute_weights;
};

struct Spread {
  double mean = 0.0;
  double std = 0.0;  ///< sample standard deviation
};
Spread spread_of(const std::vector<double>& values);

struct FilterScore {
  std::string name;
  std::vector<double> rmse;  ///< per path, per axis: the paper's metric (per_axis_rmse)
  Spread spread;
  double seconds_per_step = 0.0;  ///< wall time of the whole run over the steps it covered
};

struct TargetSpread {
  Vector<2> mean = Vector<2>::Zero();
  Vector<2> std = Vector<2>::Zero();
};

struct ExperimentResult {
  /// CVKF, EKF, EKF (printed Q), IMM, then SE, EC (absolute frame) when given, and EC.
  std::vector<FilterScore> table3;
  std::vector<FilterScore> table4;      ///< the networks on the in-range paths
  std::vector<FilterScore> beyond;      ///< every filter on the long paths
  TargetSpread ec_targets, se_targets;  ///< Table 1, over the training windows
  double beyond_range_max_m = 0.0;      ///< the farthest any long path's truth went
  double training_range_m = 0.0;        ///< the farthest any training path's truth went
  int test_paths = 0;
  bool networks = false;
  /// How each network was trained (its weights file's record), when they ran.
  std::optional<learning::LstmTrainingRecord> ec_record, se_record, ec_absolute_record;
  /// One typical test path (the IMM's median RMSE) and every filter's track over it, for the
  /// picture (the paper's Fig 8).
  int example_path = 0;
  std::vector<Vector<2>> example_truth;
  std::vector<std::pair<std::string, PositionTrack>> example_tracks;
};

/// Throws std::runtime_error when weights are named but cannot be read.
ExperimentResult run_experiment(const ExperimentSetup& setup);

}  // namespace skyfuse::paper001
