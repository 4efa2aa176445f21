#pragma once
/// \file
/// An IMM contribution on the wire: one InformationIncrement sample per mode (skyfuse_wire.idl
/// says which fields), and back. Values cross bit for bit, as in wire_conversion.hpp.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/tracking/imm_network.hpp"
#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::transport {

/// What one mode's sample carries: the mode's increment and prior, the likelihood terms, and
/// the mode probabilities of the station's prior.
template <int N, int kModes>
struct ImmModeSample {
  static constexpr int kDim = N;
  PeerContribution<N> contribution;
  LikelihoodTerms terms;
  Vector<kModes> prior_probabilities;
};

/// Mode I of `contribution` as the sample that carries it.
template <int I, typename... Modes>
wire::InformationIncrement mode_to_wire(const ImmContribution<Modes...>& contribution,
                                        std::uint64_t run_id, std::uint32_t step) {
  wire::InformationIncrement sample = to_wire(std::get<I>(contribution.modes), run_id, step);
  const auto& p = contribution.prior_probabilities;
  const LikelihoodTerms& terms = contribution.terms[I];
  sample.mode(static_cast<std::uint32_t>(I));
  sample.prior_mode_probabilities(std::vector<double>(p.data(), p.data() + p.size()));
  sample.weighted_innovation(terms.weighted_innovation);
  sample.log_det_noise(terms.log_det_noise);
  sample.measurement_dim(static_cast<std::uint32_t>(terms.measurement_dim));
  return sample;
}

/// The sample's mode part for a mode of dimension N among kModes; nothing if its lengths are
/// not those, or its dimension is not a count a sensor could measure.
template <int N, int kModes>
std::optional<ImmModeSample<N, kModes>> mode_from_wire(const wire::InformationIncrement& sample) {
  constexpr std::uint32_t kMaxMeasurementDim = 16;
  const auto contribution = contribution_from_wire<N>(sample);
  const auto probabilities = unpack_vector<kModes>(sample.prior_mode_probabilities());
  if (!contribution || !probabilities || sample.measurement_dim() > kMaxMeasurementDim) {
    return std::nullopt;
  }
  return ImmModeSample<N, kModes>{*contribution,
                                  {sample.weighted_innovation(), sample.log_det_noise(),
                                   static_cast<int>(sample.measurement_dim())},
                                  *probabilities};
}

/// The track of an IMM: the mixture's first ConstantAcceleration3D::kDim components ([p; v; a],
/// the state of its CA mode, the scenario's model; the turn rate stays inside the modes) and
/// the mode probabilities.
template <typename Filter>
wire::TrackEstimate imm_track(const Filter& imm, std::uint64_t run_id, std::uint64_t step,
                              int source_id, wire::TrackSource source,
                              std::span<const int> contributors) {
  constexpr int N = ConstantAcceleration3D::kDim;
  const auto mixture = imm.estimate();
  wire::TrackEstimate track =
      to_wire(GaussianState<N>{mixture.mean.template head<N>(),
                               mixture.covariance.template topLeftCorner<N, N>()},
              run_id, static_cast<std::uint32_t>(step), source_id, source, contributors);
  const auto& p = imm.mode_probabilities();
  track.mode_probabilities(std::vector<double>(p.data(), p.data() + p.size()));
  return track;
}

/// Whether a sample is a single-model run's: mode 0 and none of the IMM's fields.
inline bool is_single_model_sample(const wire::InformationIncrement& sample) {
  return sample.mode() == 0 && sample.prior_mode_probabilities().empty() &&
         sample.weighted_innovation() == 0.0 && sample.log_det_noise() == 0.0 &&
         sample.measurement_dim() == 0;
}

}  // namespace skyfuse::transport
