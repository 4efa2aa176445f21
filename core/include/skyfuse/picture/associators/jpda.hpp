#pragma once
/// \file
/// Joint probabilistic data association, per station: every gated detection of the station's
/// scan may update a track, weighed by its association probability beta_tj, the sum over the
/// feasible joint events of the track's cluster (each track one detection or none, each
/// detection one track or none) of the events' probabilities,
///
///   P(event) ~ prod_{t takes j} P_D N(nu_tj; 0, S_t) / lambda * prod_{t takes none} (1 - P_D P_G),
///
/// with P_D, P_G and the false-alarm density lambda the station's (DetectionPrior). Each
/// cluster's events are enumerated exactly; a cluster whose events could exceed
/// `jpda_max_events` is decided by GNN instead and counted (ScanAssociation).
///
/// Every peer computes the same probabilities from the same predicted picture and the same
/// published scan, so the picture stays bit-identical; that each station associates its own
/// scan (parallel JPDA) rather than all scans jointly is what keeps it exact between peers
/// (docs/picture.md, "JPDA").

#include "skyfuse/picture/scan_association.hpp"

namespace skyfuse {

struct AssociationConfig;

void associate_jpda(const Hypotheses& hypotheses, const DetectionPrior& prior,
                    const AssociationConfig& config, AssociationWork& work, ScanAssociation& out);

}  // namespace skyfuse
