#pragma once
// Small statistics shared by the harness's reports.

#include <algorithm>
#include <cmath>
#include <vector>

namespace skyfuse::harness {

/// Nearest-rank percentile (p in [0, 1]) of `values`; 0 for an empty set.
inline double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size())));
  return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

}  // namespace skyfuse::harness
