#pragma once
// A station's scan as the air-traffic world sends it (docs/asterix.md): a radar's plots as
// CAT048, a receiver of the aircraft's own reports as CAT021 — what `skyfuse run
// --asterix-record` writes beside the nodes' CAT062, so that a run's detections are a feed
// others can read.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "skyfuse/asterix/bytes.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/sim/picture_detections.hpp"
#include "skyfuse/traffic/geodesy.hpp"

namespace skyfuse::harness {

/// One scan's records, all of one category; none (category 0) for a sensor no item carries.
struct ScanRecords {
  std::uint8_t category = 0;
  std::vector<asterix::Bytes> records;
  /// Detections no record could hold (a value outside its item's range, an address past 24
  /// bits, a station id past SIC's 255).
  std::size_t left_out = 0;
};

/// Station `station`'s `scan` at `time_of_day_s`, each detection a record:
/// - `range_azimuth` (a 2-D primary radar): CAT048, a PSR plot, I048/040's range and azimuth
///   (clockwise from north);
/// - `range_azimuth_altitude` (a Mode S radar): CAT048, a roll-call plot, with the reported
///   altitude as I048/090's flight level and the address as I048/220;
/// - `position_velocity` (ADS-B, Remote ID): CAT021, the position through `anchor` as WGS-84
///   (I021/131) and geometric height (I021/140), the horizontal velocity (I021/160), the
///   address (I021/080; anonymous where none), and NACp/NACv from the station's noise;
/// - any other sensor (a 3-D radar's elevation, multilateration's time differences): none.
/// The data source is SAC 0 and the station's id as SIC; every record is marked simulated.
ScanRecords scan_records(const SimulatedScan& scan, const StationConfig& station,
                         double time_of_day_s, const GeoAnchor& anchor);

}  // namespace skyfuse::harness
