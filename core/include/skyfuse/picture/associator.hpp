#pragma once
/// \file
/// The data associator: the part of the tracker that turns one station's hypotheses
/// (hypothesiser.hpp) into weighted pairs (scan_association.hpp). Each associator is its own
/// files under picture/associators/ and one line of the registry (associator.cpp); a
/// scenario names one (`tracker: {associator: jpda}`), GNN by default.

#include <span>
#include <string>
#include <string_view>

#include "skyfuse/picture/scan_association.hpp"

namespace skyfuse {

struct AssociationConfig;

/// Decides `hypotheses` of a station whose sensor behaves as `prior` says, into `out`.
using AssociateFn = void (*)(const Hypotheses& hypotheses, const DetectionPrior& prior,
                             const AssociationConfig& config, AssociationWork& work,
                             ScanAssociation& out);

struct Associator {
  std::string_view name;  ///< as a scenario names it
  std::string_view summary;
  /// Whether a track may take several detections of one scan, each with a weight below 1:
  /// only a filter part whose contributions add up (an increment rule) can fuse those.
  bool weighs_pairs = false;
  /// Whether it reads the hypotheses' log-densities (the hypothesiser computes them only then).
  bool reads_densities = false;
  AssociateFn associate = nullptr;
};

/// Every associator, in the order `skyfuse` lists them.
std::span<const Associator> associators();
/// The associator a scenario names `name`; nullptr for none.
const Associator* find_associator(std::string_view name);
/// Their names, "gnn, jpda", for a message.
std::string associator_names();

}  // namespace skyfuse
