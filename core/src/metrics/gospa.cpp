#include "skyfuse/metrics/gospa.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "skyfuse/association/assignment.hpp"

namespace skyfuse {

Gospa gospa(std::span<const Vector3> truths, std::span<const Vector3> estimates,
            const GospaParameters& parameters, std::vector<int>* assignment) {
  if (!(parameters.cutoff_m > 0.0)) throw std::invalid_argument("GOSPA: the cut-off must be > 0");
  if (!(parameters.order >= 1.0)) throw std::invalid_argument("GOSPA: the order must be >= 1");
  const double p = parameters.order;
  const double cut_p = std::pow(parameters.cutoff_m, p);
  // Pairs closer than c save c^p (a miss and a false track) and cost d^p; a pair at c or
  // beyond saves nothing, so only the closer ones enter the assignment, which maximises the
  // saving: cost d^p - c^p, nothing for leaving a target unassigned.
  std::vector<association::GatedPair> pairs;
  for (std::size_t t = 0; t < truths.size(); ++t) {
    for (std::size_t e = 0; e < estimates.size(); ++e) {
      const double d = (truths[t] - estimates[e]).norm();
      if (d < parameters.cutoff_m) {
        pairs.push_back({static_cast<int>(t), static_cast<int>(e), std::pow(d, p) - cut_p});
      }
    }
  }
  const std::vector<double> unassigned(truths.size(), 0.0);
  const auto solved =
      association::solve_gated_assignment(truths.size(), estimates.size(), pairs, unassigned);

  Gospa result;
  for (std::size_t t = 0; t < truths.size(); ++t) {
    const int e = solved.column_of_row[t];
    if (e < 0) continue;
    ++result.assigned;
    result.localisation += std::pow((truths[t] - estimates[static_cast<std::size_t>(e)]).norm(), p);
  }
  if (assignment != nullptr) {
    assignment->assign(solved.column_of_row.begin(),
                       solved.column_of_row.begin() + static_cast<std::ptrdiff_t>(truths.size()));
  }
  result.missed_targets = truths.size() - result.assigned;
  result.false_estimates = estimates.size() - result.assigned;
  result.missed = 0.5 * cut_p * static_cast<double>(result.missed_targets);
  result.false_tracks = 0.5 * cut_p * static_cast<double>(result.false_estimates);
  result.distance = std::pow(result.localisation + result.missed + result.false_tracks, 1.0 / p);
  return result;
}

}  // namespace skyfuse
