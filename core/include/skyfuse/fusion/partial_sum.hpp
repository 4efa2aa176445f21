#pragma once
/// \file
/// A sum of information increments over some of a round's stations: what a cluster's aggregator
/// publishes in the tree exchange (tracking/cluster_layout.hpp), and, summed over the clusters
/// in order, the round's total that every peer fuses. Increments add, so
///
///   Y = Y_ref + T,  T = sum_c S_c,  S_c = sum_{i in c} w_i dQ_i   (and the same for y)
///
/// is the stacked filter's information, as the flat sum is, in another order of summation. Every
/// sum starts from zero and runs in a fixed order (members in ascending id, clusters in
/// ascending order), so every node that forms a sum forms the same bits, and the in-process twin
/// forms them too.

#include <span>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/fusion/information_increment.hpp"

namespace skyfuse {

/// sum += w dQ, w dy: one station's term of a sum. Every sum of the tree exchange adds its
/// stations this way, so an IMM's per-mode sums and an aggregator's form the same bits.
template <int N>
void add_weighted_increment(InformationIncrement<N>& sum, double weight,
                            const InformationIncrement<N>& increment) {
  sum.delta_information.noalias() += weight * increment.delta_information;
  sum.delta_vector.noalias() += weight * increment.delta_vector;
}

/// sum += a later cluster's sum.
template <int N>
void add_increment_sum(InformationIncrement<N>& sum, const InformationIncrement<N>& later) {
  sum.delta_information += later.delta_information;
  sum.delta_vector += later.delta_vector;
}

template <int N>
struct PartialSum {
  /// sum of w_i dQ_i and of w_i dy_i; station_id is the lowest contributor's.
  InformationIncrement<N> sum;
  /// The stations summed, ascending.
  std::vector<int> contributors;
  /// The prior of the lowest contributor's increment: the round's reference (peer_tracker.hpp).
  GaussianState<N> reference;

  bool empty() const { return contributors.empty(); }
  void clear() {
    sum.set_zero(0);
    contributors.clear();
  }

  /// Adds station `id`'s increment with its fusion weight; its prior becomes the reference if
  /// it is the first. Stations come in ascending id.
  void add(int id, double weight, const InformationIncrement<N>& increment,
           const GaussianState<N>& prior) {
    if (contributors.empty()) {
      sum.station_id = id;
      reference = prior;
    }
    add_weighted_increment(sum, weight, increment);
    contributors.push_back(id);
  }

  /// Adds a later cluster's sum (its contributors all above this one's).
  void add(const PartialSum& later) {
    if (later.empty()) return;
    if (contributors.empty()) {
      sum.station_id = later.sum.station_id;
      reference = later.reference;
    }
    add_increment_sum(sum, later.sum);
    contributors.insert(contributors.end(), later.contributors.begin(), later.contributors.end());
  }
};

}  // namespace skyfuse
