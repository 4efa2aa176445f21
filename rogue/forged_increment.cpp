#include "forged_increment.hpp"

#include <vector>

namespace skyfuse::rogue {

wire::InformationIncrement plausible_increment(std::uint64_t run, std::uint32_t step, int station,
                                               int state_dim) {
  const auto n = static_cast<std::size_t>(state_dim);
  // Upper triangles row-major: the diagonal entry (r, r) is at r n - r (r - 1) / 2.
  std::vector<double> information(n * (n + 1) / 2, 0.0);
  std::vector<double> identity(n * (n + 1) / 2, 0.0);
  for (std::size_t r = 0; r < n; ++r) identity[r * n - r * (r - 1) / 2] = 1.0;
  information[0] = 1e-4;
  wire::InformationIncrement sample;
  sample.run_id(run);
  sample.step(step);
  sample.station_id(station);
  sample.delta_information(information);
  sample.delta_vector(std::vector<double>(n, 0.0));
  sample.prior_x(std::vector<double>(n, 0.0));
  sample.prior_covariance(identity);
  return sample;
}

}  // namespace skyfuse::rogue
