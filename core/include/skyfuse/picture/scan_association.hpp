#pragma once
/// \file
/// What an associator (picture/associator.hpp) decided for one station's scan: a weight
/// for each (track, detection) pair it keeps — 1 for GNN's one detection per track, the
/// association probability beta_tj for JPDA's — and the detections no track may have produced,
/// which are left for initiation. The same inputs give the same bits at every peer.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "skyfuse/association/assignment.hpp"
#include "skyfuse/picture/address.hpp"
#include "skyfuse/picture/hypothesiser.hpp"

namespace skyfuse {

/// Track `track` (its index in picture order) takes detection `detection` with `weight`.
struct WeightedPair {
  int track = 0;
  std::uint32_t detection = 0;
  double weight = 1.0;
};

struct ScanAssociation {
  std::vector<WeightedPair> pairs;          ///< ascending track, then detection; weight > 0
  std::vector<std::uint32_t> unassociated;  ///< detections left for initiation, ascending
  std::size_t dropped = 0;                  ///< detections beyond max_detections_per_scan
  std::size_t gated_pairs = 0;
  std::size_t largest_cluster = 0;  ///< tracks of the largest cluster of competing pairs
  /// JPDA: clusters whose joint events exceeded the bound, decided by GNN instead.
  std::size_t fallback_clusters = 0;
  /// Addressed detections refused as possible spoofs (picture/identity.hpp).
  std::size_t refused_addresses = 0;
};

/// What a station's associator knows of its sensor as a sensor (its detection settings, as
/// the loader resolved them): JPDA's P_D and false-alarm density; GNN needs none.
struct DetectionPrior {
  double detection_probability = 1.0;  ///< P_D
  double gate_probability = 1.0;       ///< P_G: the share of true detections the gate keeps
  /// lambda: false alarms (and new aircraft) per unit of measurement volume, > 0.
  double clutter_density = 1e-12;
};

/// What identity (picture/identity.hpp) decided of one station's scan before the gate
/// search: the addressed detections that went to the track of their address, and those refused.
struct AddressRouting {
  std::vector<WeightedPair> routed;     ///< ascending detection; weight 1
  std::size_t refused = 0;              ///< addressed detections that failed the sanity gate
  std::vector<char> detection_decided;  ///< per detection: routed or refused; empty: none
  std::vector<char> track_taken;        ///< per track: took a routed detection; empty: none

  void clear() {
    routed.clear();
    refused = 0;
    detection_decided.clear();
    track_taken.clear();
  }
  /// The mask the gate search takes from this routing, with the tracks' and detections'
  /// addresses (each empty when none has one).
  IdentityMask mask(std::span<const Address> track_addresses,
                    std::span<const Address> detection_addresses) const {
    return {track_addresses, detection_addresses, track_taken, detection_decided};
  }
};

/// Reusable buffers of a station's association: a round allocates only when the picture grows.
struct AssociationWork {
  AddressRouting routing;
  HypothesiserWork hypothesiser;
  Hypotheses hypotheses;
  std::vector<association::GatedPair> gated;
  std::vector<double> unassigned_cost;
  std::vector<double> scratch;
};

/// What every associator does first: `out` emptied and counting `hypotheses`' dropped and gated
/// detections, and `work.gated` their pairs as the assignment solver takes them (cost: NIS).
inline void start_association(const Hypotheses& hypotheses, AssociationWork& work,
                              ScanAssociation& out) {
  out.pairs.clear();
  out.unassociated.clear();
  out.dropped = hypotheses.dropped;
  out.gated_pairs = hypotheses.pairs.size();
  out.largest_cluster = 0;
  out.fallback_clusters = 0;
  out.refused_addresses = 0;
  work.gated.clear();
  for (const Hypothesis& h : hypotheses.pairs) work.gated.push_back({h.track, h.detection, h.nis});
}

}  // namespace skyfuse
