#pragma once
/// \file
/// Where a station of a run of many aircraft takes its scans from when an ASTERIX feed gives
/// them rather than its simulator: a recorded file (`--asterix-replay`, asterix_replay.hpp) or
/// a live UDP feed (`--asterix-in`, asterix_live.hpp). Either is asked for one round's scan at
/// a time; the station does not know which it has.

#include <cstdint>
#include <memory>
#include <string>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse::transport {

class FedScans {
 public:
  virtual ~FedScans() = default;
  /// Round k's scan, with `noise` as its R; rounds are asked in ascending order.
  virtual Scan scan_at(std::uint64_t k, const DetectionNoise& noise) = 0;
  /// Where the scans come from, in a line for the station's log as it starts.
  virtual std::string started() const = 0;
  /// What the feed gave so far, in a line for the station's log.
  virtual std::string summary() const = 0;
};

/// The feed `options` name for `station` (whose sensor ASTERIX carries), or null where the
/// options name none or the sensor is one no item carries (it simulates its scans). Throws
/// std::runtime_error where the file cannot be read or the socket not opened.
std::unique_ptr<FedScans> make_fed_scans(const options::NodeOptions& options,
                                         const StationConfig& station, const Scenario& scenario);

}  // namespace skyfuse::transport
