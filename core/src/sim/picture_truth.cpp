#include "skyfuse/sim/picture_truth.hpp"

#include "skyfuse/scenario/traffic_config.hpp"

namespace skyfuse {

void aircraft_at_step(const Scenario& scenario, int stations, const std::vector<TargetTruth>& truth,
                      int k, std::vector<TruthPoint>& out) {
  out.clear();
  for (std::size_t t = 0; t < truth.size(); ++t) {
    if (!truth[t].present_at(k)) continue;
    const Vector3 p = truth[t].at(k).head<3>();
    const bool addressed = truth[t].address != kNoAddress;
    bool in_view = false;
    for (int s = 0; s < stations && !in_view; ++s) {
      const StationConfig& station = scenario.stations[static_cast<std::size_t>(s)];
      const DetectionConfig& detection = station.detection.value();
      // A cooperative sensor hears only an aircraft with an address.
      in_view = (addressed || !detection.reports_address) &&
                detection.field_of_view.contains(station.position_m, p);
    }
    out.push_back({t, p, in_view, addressed});
  }
}

}  // namespace skyfuse
