#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::transport {

wire::Measurement to_wire(const WireObservation& observation, std::uint64_t run_id,
                          std::uint32_t step) {
  wire::Measurement sample;
  sample.run_id(run_id);
  sample.step(step);
  sample.station_id(observation.station_id);
  for (int i = 0; i < 3; ++i) {
    sample.z()[i] = observation.z(i);
    sample.station_position()[i] = observation.sensor.site()(i);
  }
  pack_upper<3>(observation.noise, sample.noise().data());
  return sample;
}

WireObservation from_wire(const wire::Measurement& sample) {
  WireObservation observation;
  observation.station_id = sample.station_id();
  observation.z = Vector3(sample.z()[0], sample.z()[1], sample.z()[2]);
  observation.sensor = WireSensor(Vector3(
      sample.station_position()[0], sample.station_position()[1], sample.station_position()[2]));
  observation.noise = unpack_upper<3>(sample.noise().data());
  return observation;
}

wire::InformationIncrement to_wire(const WireContribution& contribution, std::uint64_t run_id,
                                   std::uint32_t step) {
  const InformationIncrement<9>& increment = contribution.increment;
  wire::InformationIncrement sample;
  sample.run_id(run_id);
  sample.step(step);
  sample.station_id(increment.station_id);
  pack_upper<9>(increment.delta_information, sample.delta_information().data());
  pack_upper<9>(contribution.prior.covariance, sample.prior_covariance().data());
  for (int i = 0; i < 9; ++i) {
    sample.delta_vector()[i] = increment.delta_vector(i);
    sample.prior_x()[i] = contribution.prior.mean(i);
  }
  return sample;
}

WireContribution from_wire(const wire::InformationIncrement& sample) {
  WireContribution contribution;
  InformationIncrement<9>& increment = contribution.increment;
  increment.station_id = sample.station_id();
  increment.delta_information = unpack_upper<9>(sample.delta_information().data());
  contribution.prior.covariance = unpack_upper<9>(sample.prior_covariance().data());
  for (int i = 0; i < 9; ++i) {
    increment.delta_vector(i) = sample.delta_vector()[i];
    contribution.prior.mean(i) = sample.prior_x()[i];
  }
  return contribution;
}

wire::TrackEstimate to_wire(const WireEstimate& estimate, std::uint64_t run_id, std::uint32_t step,
                            int source_id, wire::TrackSource mode,
                            std::span<const int> contributors) {
  wire::TrackEstimate sample;
  sample.run_id(run_id);
  sample.step(step);
  sample.source_id(source_id);
  sample.mode(mode);
  for (int i = 0; i < 9; ++i) sample.x()[i] = estimate.mean(i);
  pack_upper<9>(estimate.covariance, sample.covariance().data());
  sample.contributors().assign(contributors.begin(), contributors.end());
  return sample;
}

WireEstimate from_wire(const wire::TrackEstimate& sample) {
  WireEstimate estimate;
  for (int i = 0; i < 9; ++i) estimate.mean(i) = sample.x()[i];
  estimate.covariance = unpack_upper<9>(sample.covariance().data());
  return estimate;
}

}  // namespace skyfuse::transport
