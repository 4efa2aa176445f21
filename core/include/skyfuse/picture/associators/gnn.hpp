#pragma once
/// \file
/// Global nearest neighbour: each track takes at most one detection of the scan and each
/// detection goes to at most one track, at least total cost — a pair's NIS, a track left
/// without a detection the gate g — solved cluster by cluster (association/assignment.hpp).
/// Because no station's assignment constrains another's, the union of the stations'
/// assignments is the joint one, which is what keeps the network's picture the center's.

#include "skyfuse/picture/scan_association.hpp"

namespace skyfuse {

struct AssociationConfig;

void associate_gnn(const Hypotheses& hypotheses, const DetectionPrior& prior,
                   const AssociationConfig& config, AssociationWork& work, ScanAssociation& out);

}  // namespace skyfuse
