#pragma once
/// \file
/// The network IMM's rounds (imm_network.hpp declares them): a station's contribution, the
/// peers' fusion of a round and the center's stacked update. They are compiled once per
/// configuration group, for every sensor its stations may carry, in core
/// (src/tracking/filter_rounds_shard.cpp); the Monte Carlo, the station and center processes and
/// paper 000's IMM experiment only link them. Include this file to run them with another
/// sensor (a test's).

#include <optional>
#include <tuple>
#include <type_traits>
#include <vector>

#include "skyfuse/tracking/imm_network.hpp"

namespace skyfuse {

template <typename Common, typename... Modes>
template <template <int> class SensorT, int N>
OwnContribution PeerImm<Common, Modes...>::contribute(
    const StationObservation<SensorT<N>>& observation, const NisGate& gate,
    Contribution& out) const {
  out.station_id = observation.station_id;
  out.prior_probabilities = imm_.mode_probabilities();
  OwnContribution result;
  result.refused = screen_for_imm<Common>(observation, gate, [&] { return imm_.estimate(); });
  for_each_mode([&]<int I>(std::integral_constant<int, I>) {
    constexpr int kDim = std::tuple_element_t<I, std::tuple<Modes...>>::kDim;
    auto& mode = std::get<I>(out.modes);
    mode.prior = imm_.template mode_state<I>();
    if (result.refused) {
      mode.increment.set_zero(observation.station_id);
      out.terms[I] = {};
      return;
    }
    const NumericalStatus s = compute_increment(
        observation.station_id, mode.prior, sensor_for_dimension<kDim>(observation.sensor),
        observation.z, observation.noise, mode.increment, out.terms[I]);
    if (s != NumericalStatus::kOk) result.status = s;
  });
  return result;
}

template <typename Common, typename... Modes>
RoundFusion PeerImm<Common, Modes...>::fuse_round(
    std::span<const Contribution* const> contributions, std::span<const double> weights) {
  if (contributions.empty()) return {};
  if (layout_) {
    total_.clear();
    cluster_.clear();
    std::size_t current = layout_->cluster_of_id(contributions.front()->station_id);
    for (std::size_t i = 0; i < contributions.size(); ++i) {
      const std::size_t c = layout_->cluster_of_id(contributions[i]->station_id);
      if (c != current) {
        total_.add(cluster_);
        cluster_.clear();
        current = c;
      }
      cluster_.add(weights[i], *contributions[i]);
    }
    total_.add(cluster_);
    return fuse_total(total_);
  }
  const Contribution& reference = *contributions.front();
  typename Filter::ModeStates priors;
  for_each_mode([&]<int I>(std::integral_constant<int, I>) {
    std::get<I>(priors) = std::get<I>(reference.modes).prior;
  });
  return fuse_onto(priors, reference.prior_probabilities, [&](auto mode, auto& state, int& dim) {
    constexpr int I = decltype(mode)::value;
    // Mode I's increments and terms where they lie in the contributions: nothing is copied.
    const ProjectedView increments(
        contributions,
        [](const Contribution& c) -> const auto& { return std::get<I>(c.modes).increment; });
    const ProjectedView terms(
        contributions, [](const Contribution& c) -> const LikelihoodTerms& { return c.terms[I]; });
    return fuse_increments_with_likelihood(state, increments, terms, weights, state, dim);
  });
}

template <typename Common, typename... Modes>
RoundFusion PeerImm<Common, Modes...>::fuse_total(const Sum& total) {
  if (total.empty()) return {};
  return fuse_onto(
      total.references, total.prior_probabilities, [&](auto mode, auto& state, int& dim) {
        constexpr int I = decltype(mode)::value;
        constexpr double kOne = 1.0;
        return fuse_increments_with_likelihood(state, std::span(&std::get<I>(total.sums), 1),
                                               std::span(&total.terms[I], 1), std::span(&kOne, 1),
                                               state, dim);
      });
}

template <typename Common, typename... Modes>
template <typename FuseMode>
RoundFusion PeerImm<Common, Modes...>::fuse_onto(const typename Filter::ModeStates& priors,
                                                 const Vector<kModes>& probabilities,
                                                 FuseMode fuse_mode) {
  bool differs = probabilities != imm_.mode_probabilities();
  for_each_mode([&]<int I>(std::integral_constant<int, I>) {
    const auto& prior = std::get<I>(priors);
    const auto& own = imm_.template mode_state<I>();
    differs = differs || prior.mean != own.mean || prior.covariance != own.covariance;
  });
  std::optional<Filter> before;
  if (differs) {
    before = imm_;
    imm_.restore(priors, probabilities);
  }
  const NumericalStatus status = imm_.update_with([&](auto mode, auto& state) {
    int measurement_dim = 0;
    const UpdateReport report = fuse_mode(mode, state, measurement_dim);
    return ModeUpdate{report.status, report.log_likelihood(measurement_dim)};
  });
  if (status != NumericalStatus::kOk && before) imm_ = *before;
  return {status, differs && status == NumericalStatus::kOk};
}

template <typename Common, typename... Modes>
template <template <int> class SensorT, int N>
NumericalStatus CentralImm<Common, Modes...>::update(
    std::span<const StationObservation<SensorT<N>>> observations) {
  return imm_.update_with([&](auto mode, auto& state) {
    constexpr int kDim = std::decay_t<decltype(state)>::kDim;
    using ModeObservation = StationObservation<SensorT<kDim>>;
    std::vector<ModeObservation> stacked;
    stacked.reserve(observations.size());
    for (const auto& o : observations) {
      stacked.push_back({o.station_id, sensor_for_dimension<kDim>(o.sensor), o.z, o.noise});
    }
    const UpdateReport report = stacked_update_with_likelihood(state, stacked);
    mode_nis_(decltype(mode)::value) = report.nis;
    return ModeUpdate{report.status, report.log_likelihood(static_cast<int>(stacked.size()) *
                                                           SensorT<N>::kMeasDim)};
  });
}

}  // namespace skyfuse
