#include "forged_increment.hpp"

#include <vector>

#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::rogue {

wire::InformationIncrement plausible_increment(std::uint64_t run, std::uint32_t step, int station,
                                               int state_dim) {
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(state_dim, state_dim);
  information(0, 0) = 1e-4;
  wire::InformationIncrement sample;
  sample.run_id(run);
  sample.step(step);
  sample.station_id(station);
  sample.delta_information(transport::pack_upper<Eigen::Dynamic>(information));
  sample.delta_vector(std::vector<double>(static_cast<std::size_t>(state_dim), 0.0));
  sample.prior_x(std::vector<double>(static_cast<std::size_t>(state_dim), 0.0));
  sample.prior_covariance(
      transport::pack_upper<Eigen::Dynamic>(Eigen::MatrixXd::Identity(state_dim, state_dim)));
  return sample;
}

}  // namespace skyfuse::rogue
