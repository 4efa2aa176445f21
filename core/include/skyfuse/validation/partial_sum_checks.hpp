#pragma once
/// \file
/// What a node checks of a tree exchange's sum before it adds it or fuses it
/// (fusion/partial_sum.hpp): a cluster's sum from the cluster's aggregator, or a round's total.
/// Nothing may be counted twice and nothing forged: the contributors strictly ascending (no
/// station twice), every one a member of the cluster the sum claims (wrong_cluster), none already
/// counted in the sums a receiver holds (overlap); the sum itself as an increment (finite,
/// bounded, positive semi-definite, since a sum of such is such) and its reference as a prior;
/// an IMM's sum so mode by mode, with its summed likelihood terms and mode probabilities.

#include <algorithm>
#include <optional>
#include <span>

#include "skyfuse/fusion/partial_sum.hpp"
#include "skyfuse/tracking/cluster_layout.hpp"
#include "skyfuse/tracking/imm_partial_sum.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse {

/// Contributors strictly ascending and each inside `allowed` (ascending ids): why not, if not
/// (a station twice: overlap; out of order: out_of_range).
inline std::optional<DropKind> check_contributor_set(std::span<const int> contributors,
                                                     std::span<const int> allowed) {
  for (std::size_t i = 0; i < contributors.size(); ++i) {
    if (i > 0 && contributors[i] == contributors[i - 1]) return DropKind::kOverlap;
    if (i > 0 && contributors[i] < contributors[i - 1]) return DropKind::kOutOfRange;
    if (!std::binary_search(allowed.begin(), allowed.end(), contributors[i])) {
      return DropKind::kWrongCluster;
    }
  }
  return std::nullopt;
}

/// Whether two ascending contributor sets share a station.
inline bool contributors_overlap(std::span<const int> a, std::span<const int> b) {
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < a.size() && j < b.size()) {
    if (a[i] == b[j]) return true;
    a[i] < b[j] ? ++i : ++j;
  }
  return false;
}

/// The numbers of a sum, given as its increment, its contributors and its reference: the
/// increment as check_increment(), the reference as check_estimate() (an empty sum has no
/// reference to check), and its station id its lowest contributor's.
template <int N>
std::optional<DropKind> check_sum_values(const InformationIncrement<N>& sum,
                                         std::span<const int> contributors,
                                         const GaussianState<N>& reference) {
  if (const auto why = check_increment(sum)) return why;
  if (contributors.empty()) {
    const bool zero = sum.delta_information.isZero(0.0) && sum.delta_vector.isZero(0.0);
    return zero ? std::nullopt : std::optional(DropKind::kOutOfRange);
  }
  if (sum.station_id != contributors.front()) return DropKind::kOutOfRange;
  return check_estimate(reference);
}
template <int N>
std::optional<DropKind> check_sum_values(const PartialSum<N>& sum) {
  return check_sum_values(sum.sum, sum.contributors, sum.reference);
}

/// The summed likelihood terms of `contributors` stations: as check_likelihood_terms() says of
/// one station's, with the bounds of that many and room for their weights in log det R (a sum
/// of screened-out stations' is all zero).
template <int N>
std::optional<DropKind> check_summed_terms(const LikelihoodTerms& terms,
                                           const InformationIncrement<N>& sum,
                                           std::size_t contributors) {
  const auto n = static_cast<int>(contributors);
  return check_likelihood_terms(terms, sum, kMaxMeasurementDim * n, 2.0 * kMaxLogDetNoise * n);
}

/// The numbers of an IMM's sum: each mode's as check_sum_values() says of one model's, its
/// summed likelihood terms, and the reference's mode probabilities.
template <typename... Modes>
std::optional<DropKind> check_sum_values(const ImmPartialSum<Modes...>& sum) {
  std::optional<DropKind> why;
  ImmPartialSum<Modes...>::for_each_mode([&]<int I>(std::integral_constant<int, I>) {
    if (why) return;
    const auto& mode_sum = std::get<I>(sum.sums);
    why = check_sum_values(mode_sum, sum.contributors, std::get<I>(sum.references));
    if (!why) why = check_summed_terms(sum.terms[I], mode_sum, sum.contributors.size());
  });
  if (!why && !sum.empty()) why = check_mode_probabilities(sum.prior_probabilities);
  return why;
}

/// Cluster `cluster`'s sum as its aggregator sends it: contributors inside the cluster, then
/// its numbers.
template <typename Sum>
std::optional<DropKind> check_cluster_sum(const Sum& sum, const ClusterLayout& layout,
                                          std::size_t cluster) {
  if (cluster >= layout.clusters()) return DropKind::kWrongCluster;
  if (const auto why = check_contributor_set(sum.contributors, layout.members(cluster))) {
    return why;
  }
  return check_sum_values(sum);
}

/// A round's total: contributors among the run's `participants` (ascending), then its numbers.
template <typename Sum>
std::optional<DropKind> check_round_total(const Sum& total, std::span<const int> participants) {
  if (const auto why = check_contributor_set(total.contributors, participants)) return why;
  return check_sum_values(total);
}

}  // namespace skyfuse
