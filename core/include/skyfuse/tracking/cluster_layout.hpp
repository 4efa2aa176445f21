#pragma once
/// \file
/// The tree exchange's clusters (scenario `network: {exchange: tree, fanout: k}`): a run's
/// participants, in ascending id, cut into consecutive clusters of k (the last may be smaller).
/// Cluster c holds the participants at positions [c k, min((c + 1) k, M)). Every node derives
/// the same layout from the run plan, so none needs to be told who is in which cluster.

#include <algorithm>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <vector>

namespace skyfuse {

class ClusterLayout {
 public:
  /// `ascending_ids`: the participants; `fanout` >= 1 (1: every station its own cluster).
  ClusterLayout(std::span<const int> ascending_ids, std::size_t fanout)
      : ids_(ascending_ids.begin(), ascending_ids.end()), fanout_(fanout) {
    if (fanout_ == 0) throw std::invalid_argument("cluster layout: fanout must be >= 1");
  }

  std::size_t clusters() const { return (ids_.size() + fanout_ - 1) / fanout_; }
  std::size_t fanout() const { return fanout_; }
  /// The cluster of the participant at position `index` (ascending id).
  std::size_t cluster_of_index(std::size_t index) const { return index / fanout_; }
  /// Positions [first, last) of cluster c's members.
  std::size_t first_index(std::size_t c) const { return c * fanout_; }
  std::size_t end_index(std::size_t c) const { return std::min(ids_.size(), (c + 1) * fanout_); }
  /// Cluster c's members, ascending.
  std::span<const int> members(std::size_t c) const {
    return std::span(ids_).subspan(first_index(c), end_index(c) - first_index(c));
  }
  /// The cluster of station `id`, or clusters() if it is not a participant.
  std::size_t cluster_of_id(int id) const {
    const auto it = std::lower_bound(ids_.begin(), ids_.end(), id);
    if (it == ids_.end() || *it != id) return clusters();
    return cluster_of_index(static_cast<std::size_t>(it - ids_.begin()));
  }

 private:
  std::vector<int> ids_;
  std::size_t fanout_;
};

}  // namespace skyfuse
