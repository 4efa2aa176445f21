#include "skyfuse/experiments/paper001/experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "skyfuse/learning/lstm_network.hpp"
#include "skyfuse/learning/lstm_weights.hpp"

namespace skyfuse::paper001 {
namespace {

using Clock = std::chrono::steady_clock;

struct NamedFilter {
  std::string name;
  std::function<PositionTrack(const TrackedPath&)> track;
};

// Runs every filter over every path: per-path RMSE and the time per step each filter took.
std::vector<FilterScore> score(const std::vector<NamedFilter>& filters,
                               const std::vector<TrackedPath>& paths) {
  std::vector<FilterScore> out;
  for (const NamedFilter& filter : filters) {
    FilterScore s{filter.name, {}, {}, 0.0};
    std::size_t steps = 0;
    Clock::duration spent{};
    for (const TrackedPath& path : paths) {
      const auto start = Clock::now();
      const PositionTrack track = filter.track(path);
      spent += Clock::now() - start;
      steps += track.size() - 1;
      s.rmse.push_back(per_axis_rmse(path, track));
    }
    s.spread = spread_of(s.rmse);
    s.seconds_per_step = std::chrono::duration<double>(spent).count() / static_cast<double>(steps);
    out.push_back(std::move(s));
  }
  return out;
}

// Mean and sample standard deviation, per axis, of the targets added.
class TargetAccumulator {
 public:
  void add(const Vector<2>& target) {
    ++count_;
    sum_ += target;
    squares_ += target.cwiseProduct(target);
  }
  TargetSpread spread() const {
    if (count_ == 0) return {};
    const double n = static_cast<double>(count_);
    const Vector<2> mean = sum_ / n;
    const Vector<2> variance = (squares_ - n * mean.cwiseProduct(mean)) / std::max(n - 1.0, 1.0);
    return {mean, variance.cwiseSqrt()};
  }

 private:
  std::size_t count_ = 0;
  Vector<2> sum_ = Vector<2>::Zero();
  Vector<2> squares_ = Vector<2>::Zero();
};

double farthest(const TrackedPath& path) {
  double out = 0.0;
  for (const Vector<5>& x : path.path.truth) out = std::max(out, x.head<2>().cwiseAbs().maxCoeff());
  return out;
}

}  // namespace

Spread spread_of(const std::vector<double>& values) {
  if (values.empty()) return {};
  double mean = 0.0;
  for (const double v : values) mean += v;
  mean /= static_cast<double>(values.size());
  double squares = 0.0;
  for (const double v : values) squares += (v - mean) * (v - mean);
  const double n = static_cast<double>(values.size());
  return {mean, values.size() > 1 ? std::sqrt(squares / (n - 1.0)) : 0.0};
}

ExperimentResult run_experiment(const ExperimentSetup& setup) {
  ExperimentResult result;
  const DataSetup& data = setup.data;

  // Table 1, what the networks were trained to output, and how far the training paths went:
  // one pass over the training paths, each tracked once, reading only the windows' targets.
  TargetAccumulator ec_targets;
  TargetAccumulator se_targets;
  for (const int index : paths_in(data, Split::kTrain)) {
    const TrackedPath path = track_path(data, index);
    result.training_range_m = std::max(result.training_range_m, farthest(path));
    const int steps = static_cast<int>(path.cvkf.size());
    for (int last = kWindowSteps - 1; last < steps; last += setup.table1_stride) {
      ec_targets.add(window_target(path, last, Network::kErrorCompensation));
      se_targets.add(window_target(path, last, Network::kStateEstimation));
    }
  }
  result.ec_targets = ec_targets.spread();
  result.se_targets = se_targets.spread();

  std::vector<NamedFilter> filters = {
      {"CVKF", [](const TrackedPath& p) { return cvkf_track(p); }},
      {"EKF",
       [&](const TrackedPath& p) {
         return ekf_track(data, p, TurnRateNoise::kPositiveSemidefinite);
       }},
      {"EKF (printed Q)",
       [&](const TrackedPath& p) { return ekf_track(data, p, TurnRateNoise::kPrinted); }},
      {"IMM", [&](const TrackedPath& p) { return imm_track(data, p); }},
  };
  const std::size_t first_network = filters.size();
  std::unique_ptr<learning::LstmNetwork> se;
  std::unique_ptr<learning::LstmNetwork> ec;
  std::unique_ptr<learning::LstmNetwork> ec_absolute;
  if (setup.se_weights && setup.ec_weights) {
    se = std::make_unique<learning::LstmNetwork>(learning::read_lstm_weights(*setup.se_weights));
    ec = std::make_unique<learning::LstmNetwork>(learning::read_lstm_weights(*setup.ec_weights));
    filters.push_back({"SE", [&](const TrackedPath& p) {
                         return network_track(p, *se, Network::kStateEstimation);
                       }});
    if (setup.ec_absolute_weights) {
      ec_absolute = std::make_unique<learning::LstmNetwork>(
          learning::read_lstm_weights(*setup.ec_absolute_weights));
      filters.push_back({"EC (absolute frame)", [&](const TrackedPath& p) {
                           return network_track(p, *ec_absolute, Network::kErrorCompensation);
                         }});
      result.ec_absolute_record = ec_absolute->record();
    }
    filters.push_back({"EC", [&](const TrackedPath& p) {
                         return network_track(p, *ec, Network::kErrorCompensation);
                       }});
    result.networks = true;
    result.se_record = se->record();
    result.ec_record = ec->record();
  }

  // Table 3 over the test split.
  std::vector<int> test = paths_in(data, Split::kTest);
  if (setup.test_paths > 0 && setup.test_paths < static_cast<int>(test.size())) {
    test.resize(static_cast<std::size_t>(setup.test_paths));
  }
  std::vector<TrackedPath> paths;
  paths.reserve(test.size());
  for (const int index : test) paths.push_back(track_path(data, index));
  result.test_paths = static_cast<int>(paths.size());
  result.table3 = score(filters, paths);

  // Table 4: the test paths that never leave +-in_range_m.
  std::vector<TrackedPath> in_range;
  for (const TrackedPath& p : paths) {
    if (static_cast<int>(in_range.size()) == setup.in_range_paths) break;
    if (farthest(p) <= setup.in_range_m) in_range.push_back(p);
  }
  if (result.networks) {
    result.table4 = score(
        {filters.begin() + static_cast<std::ptrdiff_t>(first_network), filters.end()}, in_range);
  }

  // Long paths from another seed: the same kinematics, flown far past the training range.
  DataSetup far = data;
  far.seed = data.seed + 1;
  far.path.steps = data.path.steps * setup.beyond_range_length;
  far.paths = setup.beyond_range_paths;
  std::vector<TrackedPath> beyond;
  for (int i = 0; i < setup.beyond_range_paths; ++i) {
    beyond.push_back(track_path(far, i));
    result.beyond_range_max_m = std::max(result.beyond_range_max_m, farthest(beyond.back()));
  }
  result.beyond = score(filters, beyond);

  // The example, like the paper's Fig 8: a typical path, the one whose IMM RMSE is the test
  // set's median.
  const FilterScore& imm = result.table3[3];
  std::vector<double> sorted = imm.rmse;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  const double median = sorted[sorted.size() / 2];
  const std::size_t example = static_cast<std::size_t>(
      std::find(imm.rmse.begin(), imm.rmse.end(), median) - imm.rmse.begin());
  result.example_path = test[example];
  for (const Vector<5>& x : paths[example].path.truth)
    result.example_truth.emplace_back(x.head<2>());
  for (const NamedFilter& f : filters)
    result.example_tracks.emplace_back(f.name, f.track(paths[example]));
  return result;
}

}  // namespace skyfuse::paper001
