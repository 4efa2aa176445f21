#pragma once
/// \file
/// In-process Monte-Carlo evaluation: both architectures (stacked-measurement EKF and
/// peer-to-peer information fusion) on the same simulated measurements, run by the same core
/// code the station and fusion-center processes use.

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/metrics/chi_square.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/scenario/truth.hpp"
#include "skyfuse/validation/nis_gate.hpp"

namespace skyfuse {

/// A filter step failed; the message names the architecture, the step and the station.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An estimate of whatever dimension the scenario's motion model has, viewed in place.
struct EstimateView {
  Eigen::Map<const Eigen::VectorXd> mean;
  Eigen::Map<const Eigen::MatrixXd> covariance;

  template <int N>
  static EstimateView of(const GaussianState<N>& state) {
    return {Eigen::Map<const Eigen::VectorXd>(state.mean.data(), N),
            Eigen::Map<const Eigen::MatrixXd>(state.covariance.data(), N, N)};
  }
};

/// What one step of one run produced, for callers that want more than the summary.
struct StepRecord {
  int step;
  const Vector<kKinematicsDim>& truth;  ///< true kinematics [p; v; a]
  EstimateView central;
  EstimateView decentralised;
  double nis_central;
  /// The two estimates' positions (models/state_position.hpp).
  Vector3 position_central;
  Vector3 position_p2p;
};
using StepObserver = std::function<void(const StepRecord&)>;

/// Per-step traces of one run (index = step).
struct RunTrace {
  std::vector<double> sq_error_central;  ///< |p - p_hat|^2, stacked EKF
  std::vector<double> sq_error_p2p;      ///< |p - p_hat|^2, fused increments
  std::vector<double> nees_p2p;          ///< NEES of the fused estimate (state dof; IMM: [p; v])
  std::vector<double> nis_central;       ///< NIS of the stacked update (sum of the sensors' dof)
  double max_abs_diff_m = 0.0;           ///< max over steps of |p_central - p_p2p|
  /// Measurements screened out (checks or NIS gate): by the stations' own screening against
  /// the common prior, and by the center's against its own.
  int refused_p2p = 0;
  int refused_central = 0;
};

/// One run using the first `stations` stations of the scenario, with the motion model and
/// sensors it names. Step k updates with the measurements of step k by the round rule
/// (tracking/round_rule.hpp, with `gate`), records, then predicts to k+1; steps =
/// scenario.steps. This is the in-process twin of a lock-step `skyfuse run`.
RunTrace simulate_run(const Scenario& scenario, const TruthTrajectory& truth, int stations,
                      std::uint64_t run, const StepObserver& observer = {},
                      const NisGate& gate = {});

struct MonteCarloSettings {
  /// Station counts M to evaluate (each uses the first M stations). All counts of one run see
  /// the same measurements, simulated once.
  std::vector<int> stations = {1};
  double speed_mps = 0.0;
  int runs = 1;
  int threads = 1;
};

struct MonteCarloSummary {
  int stations = 0;
  double speed_mps = 0.0;
  int runs = 0;
  int steps = 0;
  /// sqrt of the mean over all runs and steps of |p - p_hat|^2.
  double rmse_central_m = 0.0;
  double rmse_p2p_m = 0.0;
  /// max over runs and steps of |p_central - p_p2p|.
  double max_abs_diff_m = 0.0;
  /// ANEES: per step, NEES averaged over runs; then averaged over steps.
  double anees = 0.0;
  ChiSquareBand anees_band;          ///< 95 % band of a per-step ANEES over `runs` runs
  double anees_steps_in_band = 0.0;  ///< fraction of steps whose ANEES lies in the band
  /// Mean NIS of the stacked update divided by its dof (the M sensors' components together):
  /// 1 when consistent.
  double anis_per_dof = 0.0;
};

/// Runs `settings.runs` runs, spread over `settings.threads` threads; returns one summary per
/// station count, in the order given. Runs are reduced in run order, so the result does not
/// depend on the thread count. `on_run_done` is called (from a worker, serialised) after each
/// run, which covers every station count.
std::vector<MonteCarloSummary> run_monte_carlo(const Scenario& scenario,
                                               const MonteCarloSettings& settings,
                                               const std::function<void()>& on_run_done = {});

}  // namespace skyfuse
