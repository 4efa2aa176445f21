#include "skyfuse/validation/nis_gate.hpp"

#include <stdexcept>

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/metrics/chi_square.hpp"

namespace skyfuse {

std::optional<double> measurement_nis(const GaussianState<9>& prior, const StationSensor& sensor,
                                      const Vector3& z, const Covariance<3>& noise) {
  const Matrix<3, 9> h = sensor.jacobian(prior.mean);
  const Vector3 innovation = sensor.residual(z, sensor.predict(prior.mean));
  const Covariance<3> s = h * prior.covariance * h.transpose() + noise;
  SmallCholesky<3> factor;
  if (!factor.compute(s)) return std::nullopt;
  return innovation.dot(factor.solve(innovation));
}

NisGate NisGate::at_probability(double probability) {
  if (!(probability > 0.0 && probability < 1.0)) {
    throw std::invalid_argument("NIS gate: the probability must be in (0, 1)");
  }
  NisGate gate;
  gate.threshold_ = chi_square_quantile(probability, 3.0);
  gate.probability_ = probability;
  return gate;
}

bool NisGate::refuses(const GaussianState<9>& prior, const StationSensor& sensor, const Vector3& z,
                      const Covariance<3>& noise) const {
  if (!enabled()) return false;
  const std::optional<double> nis = measurement_nis(prior, sensor, z, noise);
  return !nis || *nis > threshold_;
}

}  // namespace skyfuse
