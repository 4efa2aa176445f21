#pragma once
/// \file
/// A station's scan as the air-traffic world sends it (docs/asterix.md) — a radar's plots as
/// CAT048, a receiver of the aircraft's own reports as CAT021 — and back: what `skyfuse run
/// --asterix-record` writes beside the nodes' CAT062, so that a run's detections are a feed
/// others can read, and what a station would take from such a feed.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "skyfuse/asterix/bytes.hpp"
#include "skyfuse/asterix/cat021.hpp"
#include "skyfuse/asterix/cat048.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/sim/picture_detections.hpp"
#include "skyfuse/traffic/geodesy.hpp"

namespace skyfuse::transport {

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
///   altitude as I048/090's flight level, the address as I048/220 and the callsign as
///   I048/240 (where the detection has one);
/// - `position_velocity` (ADS-B, Remote ID): CAT021, the position through the scenario's
///   `anchor` as WGS-84 (I021/131) and geometric height (I021/140), the horizontal velocity
///   (I021/160) and the vertical rate (I021/157), the address (I021/080; anonymous where none),
///   the callsign (I021/170, where the detection has one), and NACp/NACv from the station's
///   noise;
/// - any other sensor (a 3-D radar's elevation, multilateration's time differences): none.
/// The data source is station_source's (the scenario's SAC, the station's id as SIC); every
/// record is marked simulated.
ScanRecords scan_records(const SimulatedScan& scan, const StationConfig& station,
                         double time_of_day_s, const Scenario& scenario);

/// Station `station_id`'s data source: the scenario's SAC (`asterix`), and its id as SIC;
/// nullopt for an id past SIC's 255.
std::optional<asterix::DataSource> station_source(const Scenario& scenario, int station_id);

/// Whether a sensor kind's detections travel as CAT048 plots or CAT021 reports (scan_records).
bool carried_by_asterix(std::string_view sensor_kind);

/// The inverse: decoded plots (CAT048) or reports (CAT021) as the detections of a scan of a
/// station of `sensor_kind`, in the scenario's frame and units — range (m) and azimuth
/// (counter-clockwise from east, rad) of a radar, the flight level as the altitude (m), the
/// address and the callsign of a Mode S radar; a report's position in east-north-up through
/// `anchor`, its velocity from the ground vector and the vertical rate (0 where a report has none),
/// its address, its callsign (I021/170, where it has one) and the σ its quality indicators state
/// (I021/090: NACp of the horizontal position, NACv of the horizontal velocity, each bound over
/// √χ²₂(0.95); Scan::reported_std). A plot or report that cannot be one
/// (a Mode S plot without a flight level, a report without a ground vector or height) is skipped
/// and counted in `skipped`. nullopt for a sensor no item carries.
std::optional<Scan> scan_of_plots(int station_id, std::string_view sensor_kind,
                                  std::span<const asterix::RadarPlot> plots, std::size_t& skipped);
std::optional<Scan> scan_of_reports(int station_id, std::span<const asterix::AdsbReport> reports,
                                    const GeoAnchor& anchor, std::size_t& skipped);

/// `scan` as ASTERIX carries it: through its records and back, each value quantised to its
/// item's resolution — the scan a station fed those records holds. Quantising it again gives
/// the same bits. nullopt for a sensor no item carries.
std::optional<Scan> quantised_as_asterix(const SimulatedScan& scan, const StationConfig& station,
                                         const Scenario& scenario);

}  // namespace skyfuse::transport
