#pragma once
/// \file
/// An IMM run by a network of stations, two ways that must agree:
///
///  - PeerImm: every peer holds the same IMM. After the common predict (mixing included, the
///    same bits everywhere) each station turns its measurement into one contribution: per
///    mode, its information increment against that mode's prior and the two scalars the mode
///    likelihood needs (fused_likelihood.hpp). Every peer fuses all contributions mode by mode
///    in ascending station id and so computes the same posteriors and mode probabilities.
///  - CentralImm: one IMM whose modes each take the stacked EKF update of all measurements,
///    weighing the modes by the stacked likelihood.
///
/// In exact arithmetic the two are the same filter; tests hold them within 1e-9.

#include <array>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "skyfuse/core/indirect_view.hpp"
#include "skyfuse/filters/imm.hpp"
#include "skyfuse/fusion/fused_likelihood.hpp"
#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/fusion/stacked_likelihood.hpp"
#include "skyfuse/fusion/station_observation.hpp"

namespace skyfuse {

/// The same sensor (same site) for a model of another state dimension. Every mode keeps the
/// position first, which is all a station's sensor reads.
template <int M, template <int> class SensorT, int N>
SensorT<M> sensor_for_dimension(const SensorT<N>& sensor) {
  if constexpr (SensorT<N>::kNeedsSite) {
    return SensorT<M>(sensor.site());
  } else {
    return SensorT<M>{};
  }
}

/// One station's contribution to a round of a PeerImm: per mode, an increment and its
/// likelihood terms.
template <typename... Modes>
struct ImmContribution {
  int station_id = 0;
  std::tuple<InformationIncrement<Modes::kDim>...> increments;
  std::array<LikelihoodTerms, sizeof...(Modes)> terms{};
};

template <typename Common, typename... Modes>
class PeerImm {
 public:
  using Filter = Imm<Common, Modes...>;
  using Contribution = ImmContribution<Modes...>;
  static constexpr int kModes = sizeof...(Modes);

  explicit PeerImm(Filter imm) : imm_(std::move(imm)) {}

  /// Mixing and every mode's time update.
  void predict() { imm_.predict(); }

  /// This station's contribution for `observation` against the current (common) mode priors.
  template <template <int> class SensorT, int N>
  NumericalStatus contribute(const StationObservation<SensorT<N>>& observation,
                             Contribution& out) const {
    out.station_id = observation.station_id;
    NumericalStatus status = NumericalStatus::kOk;
    [&]<int... I>(std::integer_sequence<int, I...>) {
      (
          [&] {
            constexpr int kDim = std::tuple_element_t<I, std::tuple<Modes...>>::kDim;
            const NumericalStatus s =
                compute_increment(observation.station_id, imm_.template mode_state<I>(),
                                  sensor_for_dimension<kDim>(observation.sensor), observation.z,
                                  observation.noise, std::get<I>(out.increments), out.terms[I]);
            if (s != NumericalStatus::kOk) status = s;
          }(),
          ...);
    }
    (std::make_integer_sequence<int, kModes>{});
    return status;
  }

  /// Fuses one round: `contributions` in ascending station id, weights[i] for the i-th.
  NumericalStatus fuse(std::span<const Contribution* const> contributions,
                       std::span<const double> weights) {
    return imm_.update_with([&](auto mode, auto& state) {
      constexpr int I = decltype(mode)::value;
      // Mode I's increments and terms where they lie in the contributions: nothing is copied.
      const ProjectedView increments(
          contributions,
          [](const Contribution& c) -> const auto& { return std::get<I>(c.increments); });
      const ProjectedView terms(contributions, [](const Contribution& c) -> const LikelihoodTerms& {
        return c.terms[I];
      });
      int measurement_dim = 0;
      const UpdateReport report = fuse_increments_with_likelihood(state, increments, terms, weights,
                                                                  state, measurement_dim);
      return ModeUpdate{report.status, report.log_likelihood(measurement_dim)};
    });
  }

  const Filter& filter() const { return imm_; }

 private:
  Filter imm_;
};

template <typename Common, typename... Modes>
class CentralImm {
 public:
  using Filter = Imm<Common, Modes...>;

  explicit CentralImm(Filter imm) : imm_(std::move(imm)) {}

  void predict() { imm_.predict(); }

  /// Every mode takes the stacked update of `observations` (ascending station id).
  template <template <int> class SensorT, int N>
  NumericalStatus update(std::span<const StationObservation<SensorT<N>>> observations) {
    return imm_.update_with([&](auto mode, auto& state) {
      constexpr int kDim = std::decay_t<decltype(state)>::kDim;
      using ModeObservation = StationObservation<SensorT<kDim>>;
      static_cast<void>(mode);
      std::vector<ModeObservation> stacked;
      stacked.reserve(observations.size());
      for (const auto& o : observations) {
        stacked.push_back({o.station_id, sensor_for_dimension<kDim>(o.sensor), o.z, o.noise});
      }
      const UpdateReport report = stacked_update_with_likelihood(state, stacked);
      return ModeUpdate{report.status, report.log_likelihood(static_cast<int>(stacked.size()) *
                                                             SensorT<N>::kMeasDim)};
    });
  }

  const Filter& filter() const { return imm_; }

 private:
  Filter imm_;
};

}  // namespace skyfuse
