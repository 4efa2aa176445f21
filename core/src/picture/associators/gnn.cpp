#include "skyfuse/picture/associators/gnn.hpp"

namespace skyfuse {

void associate_gnn(const Hypotheses& hypotheses, const DetectionPrior& /*prior*/,
                   const AssociationConfig& /*config*/, AssociationWork& work,
                   ScanAssociation& out) {
  start_association(hypotheses, work, out);
  work.unassigned_cost.assign(hypotheses.tracks, hypotheses.gate);
  const association::GatedAssignment solved = association::solve_gated_assignment(
      hypotheses.tracks, hypotheses.detections, work.gated, work.unassigned_cost);
  out.largest_cluster = solved.largest_cluster;
  out.pairs.reserve(hypotheses.tracks);
  std::vector<char> associated(hypotheses.detections, 0);
  for (std::size_t t = 0; t < hypotheses.tracks; ++t) {
    const int j = solved.column_of_row[t];
    if (j < 0) continue;
    out.pairs.push_back({static_cast<int>(t), static_cast<std::uint32_t>(j), 1.0});
    associated[static_cast<std::size_t>(j)] = 1;
  }
  for (std::uint32_t j = 0; j < hypotheses.detections; ++j) {
    if (!associated[j]) out.unassociated.push_back(j);
  }
}

}  // namespace skyfuse
