#pragma once
/// \file
/// One station's contribution to a round of the network IMM (imm_network.hpp), and a sum of
/// such contributions over some of a round's stations: the IMM's partial sum in the tree
/// exchange (fusion/partial_sum.hpp has the single-model one). Per mode, the weighted
/// increments add and so do their likelihood terms (fused_likelihood.hpp), so
///
///   T_I = sum_c S_{c,I},  S_{c,I} = sum_{i in c} w_i dQ_{i,I}   (and the same for y and terms)
///
/// gives every mode I the stacked update and its likelihood, in the tree's fixed order of
/// summation. The reference is the lowest contributor's: its mode priors and the mode
/// probabilities they were mixed with.

#include <array>
#include <tuple>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/fusion/fused_likelihood.hpp"
#include "skyfuse/fusion/partial_sum.hpp"
#include "skyfuse/tracking/peer_contribution.hpp"

namespace skyfuse {

/// One station's contribution to a round of a PeerImm: per mode, an increment and the mode's
/// prior it was computed against, and the likelihood terms; and the mode probabilities of that
/// prior.
template <typename... Modes>
struct ImmContribution {
  static constexpr int kModes = sizeof...(Modes);
  int station_id = 0;
  std::tuple<PeerContribution<Modes::kDim>...> modes;
  std::array<LikelihoodTerms, kModes> terms{};
  Vector<kModes> prior_probabilities = Vector<kModes>::Zero();
};

template <typename... Modes>
struct ImmPartialSum {
  static constexpr int kModes = sizeof...(Modes);
  using Contribution = ImmContribution<Modes...>;

  /// Per mode, sum of w_i dQ_i and of w_i dy_i (station_id: the lowest contributor's).
  std::tuple<InformationIncrement<Modes::kDim>...> sums;
  /// Per mode, the summed likelihood terms.
  std::array<LikelihoodTerms, kModes> terms{};
  /// The stations summed, ascending.
  std::vector<int> contributors;
  /// The lowest contributor's mode priors and their mode probabilities.
  std::tuple<GaussianState<Modes::kDim>...> references;
  Vector<kModes> prior_probabilities = Vector<kModes>::Zero();

  bool empty() const { return contributors.empty(); }
  void clear() {
    for_each_mode([&]<int I>(std::integral_constant<int, I>) { std::get<I>(sums).set_zero(0); });
    terms = {};
    contributors.clear();
  }

  /// This sum is station `one`'s contribution alone, unweighted: what a member sends its
  /// aggregator, which weighs it.
  void assign(const Contribution& one) {
    clear();
    for_each_mode([&]<int I>(std::integral_constant<int, I>) {
      std::get<I>(sums) = std::get<I>(one.modes).increment;
      terms[I] = one.terms[I];
    });
    take_reference(one);
    contributors.push_back(one.station_id);
  }

  /// Adds a station's contribution with its fusion weight; its priors become the reference if
  /// it is the first. Stations come in ascending id.
  void add(double weight, const Contribution& contribution) {
    if (contributors.empty()) take_reference(contribution);
    for_each_mode([&]<int I>(std::integral_constant<int, I>) {
      add_weighted_increment(std::get<I>(sums), weight, std::get<I>(contribution.modes).increment);
      add_weighted_terms(terms[I], contribution.terms[I], weight);
    });
    contributors.push_back(contribution.station_id);
  }

  /// Adds a later cluster's sum (its contributors all above this one's).
  void add(const ImmPartialSum& later) {
    if (later.empty()) return;
    if (contributors.empty()) {
      references = later.references;
      prior_probabilities = later.prior_probabilities;
      for_each_mode([&]<int I>(std::integral_constant<int, I>) {
        std::get<I>(sums).station_id = std::get<I>(later.sums).station_id;
      });
    }
    for_each_mode([&]<int I>(std::integral_constant<int, I>) {
      add_increment_sum(std::get<I>(sums), std::get<I>(later.sums));
      add_terms(terms[I], later.terms[I]);
    });
    contributors.insert(contributors.end(), later.contributors.begin(), later.contributors.end());
  }

  /// fn(std::integral_constant<int, I>{}) for every mode I, in order.
  template <typename Fn>
  static void for_each_mode(Fn&& fn) {
    [&]<int... I>(std::integer_sequence<int, I...>) {
      (fn(std::integral_constant<int, I>{}), ...);
    }
    (std::make_integer_sequence<int, kModes>{});
  }

 private:
  void take_reference(const Contribution& first) {
    for_each_mode([&]<int I>(std::integral_constant<int, I>) {
      std::get<I>(references) = std::get<I>(first.modes).prior;
      std::get<I>(sums).station_id = first.station_id;
    });
    prior_probabilities = first.prior_probabilities;
  }
};

}  // namespace skyfuse
