#include "skyfuse/scenario/measurement_simulation.hpp"

namespace skyfuse {

double draw_noise_scale(const NoiseScaleConfig& config, std::uint64_t seed, std::uint64_t run,
                        int station_id) {
  if (config.model == NoiseScaleConfig::Model::kNone) return 1.0;
  // Truncated normal by rejection: a draw fails with P(1 + delta < floor) = Phi(floor - 1),
  // at most 0.5 for the floors the loader accepts (<= 1), so all 200 draws fail with
  // probability at most 0.5^200 ~ 6e-61 (0.18^200 ~ 1e-147 at the default floor 0.1). The
  // fallback keeps the contract (a positive scale) even then.
  CounterRng rng({seed, run, static_cast<std::uint64_t>(station_id), 0, NoiseStream::kNoiseScale});
  for (int attempt = 0; attempt < 200; ++attempt) {
    const double scale = 1.0 + rng.normal();
    if (scale >= config.floor) return scale;
  }
  return config.floor;
}

Eigen::MatrixXd station_noise_covariance(const Scenario& scenario, const StationConfig& station,
                                         std::uint64_t run) {
  const double scale = draw_noise_scale(scenario.noise_scale, scenario.seed, run, station.id);
  return (scale * station.sensor.noise_std.array().square()).matrix().asDiagonal();
}

Eigen::VectorXd initial_state_error(const Scenario& scenario, std::uint64_t run) {
  if (scenario.filter.initial_state_error) return *scenario.filter.initial_state_error;
  const Eigen::VectorXd& p0 = scenario.filter.initial_covariance_diag;
  CounterRng rng({scenario.seed, run, 0, 0, NoiseStream::kInitialState});
  Eigen::VectorXd error(p0.size());
  for (Eigen::Index i = 0; i < p0.size(); ++i) error(i) = std::sqrt(p0(i)) * rng.normal();
  return error;
}

}  // namespace skyfuse
