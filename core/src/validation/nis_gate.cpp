#include "skyfuse/validation/nis_gate.hpp"

#include <stdexcept>

#include "skyfuse/metrics/chi_square.hpp"

namespace skyfuse {

NisGate NisGate::at_probability(double probability) {
  if (!(probability > 0.0 && probability < 1.0)) {
    throw std::invalid_argument("NIS gate: the probability must be in (0, 1)");
  }
  NisGate gate;
  for (int dof = 1; dof <= kMaxDof; ++dof) {
    gate.thresholds_[static_cast<std::size_t>(dof)] =
        chi_square_quantile(probability, static_cast<double>(dof));
  }
  gate.probability_ = probability;
  return gate;
}

}  // namespace skyfuse
