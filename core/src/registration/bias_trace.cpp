#include "skyfuse/registration/bias_trace.hpp"

#include <cmath>

namespace skyfuse {

double bias_entry(const SensorBias& bias, std::size_t entry) {
  return entry < SensorBias::kComponents.size() ? bias.offset(entry) : bias.time_s;
}

bool within_sigmas(const BiasTrace& trace, std::size_t round, double sigmas) {
  for (std::size_t e = 0; e < BiasTrace::kEntries.size(); ++e) {
    if (!trace.estimated[e]) continue;
    const double error = bias_entry(trace.estimate[round], e) - bias_entry(trace.truth, e);
    if (!(std::abs(error) <= sigmas * bias_entry(trace.sigma[round], e))) return false;
  }
  return true;
}

int converged_from(const BiasTrace& trace, double sigmas) {
  int from = -1;
  for (std::size_t k = trace.estimate.size(); k-- > 0;) {
    if (!within_sigmas(trace, k, sigmas)) break;
    from = static_cast<int>(k);
  }
  return from;
}

}  // namespace skyfuse
