#include "skyfuse/transport/fed_scans.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "skyfuse/asterix/udp.hpp"
#include "skyfuse/transport/asterix_live.hpp"
#include "skyfuse/transport/asterix_replay.hpp"
#include "skyfuse/transport/scan_asterix.hpp"

namespace skyfuse::transport {

std::unique_ptr<FedScans> make_fed_scans(const options::NodeOptions& options,
                                         const StationConfig& station, const Scenario& scenario) {
  if (!carried_by_asterix(station.sensor.kind)) return nullptr;
  if (!options.asterix_replay.empty()) {
    return std::make_unique<ReplayedScans>(options.asterix_replay, scenario, station);
  }
  if (!options.asterix_in.empty()) {
    std::string error;
    const auto listen = asterix::parse_udp_endpoint(options.asterix_in, error);
    if (!listen) throw std::invalid_argument("--asterix-in: " + error);
    const auto wait = std::chrono::milliseconds(std::llround(options.asterix_in_wait_ms));
    return std::make_unique<LiveScans>(*listen, wait, scenario, station);
  }
  return nullptr;
}

}  // namespace skyfuse::transport
