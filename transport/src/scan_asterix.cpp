#include "skyfuse/transport/scan_asterix.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "skyfuse/asterix/data_block.hpp"
#include "skyfuse/asterix/datagram.hpp"
#include "skyfuse/asterix/pcap.hpp"
#include "skyfuse/asterix/quality.hpp"
#include "skyfuse/picture/address.hpp"

namespace skyfuse::transport {
namespace {

constexpr double kFootM = 0.3048;
constexpr double kDegPerRad = 180.0 / std::numbers::pi;

// The scenario's azimuth (counter-clockwise from east) as ASTERIX's (clockwise from north),
// and back into (-π, π].
double bearing_deg(double azimuth_rad) {
  return std::fmod(90.0 - azimuth_rad * kDegPerRad + 360.0, 360.0);
}
double azimuth_rad(double bearing_deg) {
  return std::remainder(90.0 - bearing_deg, 360.0) / kDegPerRad;
}

// A scan of which no detection has an address (an identification, a stated σ) holds none
// (picture/scan.hpp).
void drop_what_no_detection_has(Scan& scan) {
  if (std::ranges::all_of(scan.addresses, [](Address a) { return a == kNoAddress; })) {
    scan.addresses.clear();
  }
  if (std::ranges::all_of(scan.identifications,
                          [](Identification i) { return i == kNoIdentification; })) {
    scan.identifications.clear();
  }
  if (std::ranges::all_of(scan.reported_std, [](const Detection& s) { return s.isZero(); })) {
    scan.reported_std.clear();
  }
}

// The σ a report's quality indicators (I021/090) state of each value of a `position_velocity`
// detection (east, north, up, and their rates), 0 where they state none: NACp bounds the 95 %
// horizontal position error and NACv the horizontal velocity's, and σ per axis is the bound over
// √χ²₂(0.95) (asterix/quality.hpp) — the bound itself, so a σ no smaller than the aircraft's.
// Nothing bounds the height or the vertical rate here: those keep the station's noise.
Detection stated_std(const asterix::AdsbQuality& quality) {
  Detection std_of = Detection::Zero(6);
  if (const auto epu = asterix::epu_of_nacp(quality.nacp)) {
    std_of(0) = std_of(1) = *epu / asterix::kHorizontal95;
  }
  if (const auto error = asterix::error_of_nacv(quality.nucr_or_nacv)) {
    std_of(3) = std_of(4) = *error / asterix::kHorizontal95;
  }
  return std_of;
}

void add(ScanRecords& out, asterix::Encoded encoded) {
  if (encoded) {
    out.records.push_back(std::move(encoded.bytes));
  } else {
    ++out.left_out;
  }
}

ScanRecords radar_plots(const SimulatedScan& scan, asterix::DataSource source, double time_of_day_s,
                        bool mode_s) {
  ScanRecords out{asterix::kCat048, {}, 0};
  for (std::size_t j = 0; j < scan.scan.detections.size(); ++j) {
    const Detection& z = scan.scan.detections[j];
    asterix::RadarPlot plot;
    plot.source = source;
    plot.time_of_day_s = time_of_day_s;
    plot.simulated = true;
    plot.detection =
        mode_s ? asterix::DetectionType::mode_s_roll_call : asterix::DetectionType::psr;
    plot.range_m = z(0);
    plot.azimuth_deg = bearing_deg(z(1));
    if (mode_s) {
      plot.flight_level = z(2) / kFootM / 100.0;
      const Address address = address_of(scan.scan.addresses, j);
      if (address != kNoAddress) plot.address = address;
      if (const Identification id = identification_at(scan.scan.identifications, j);
          id != kNoIdentification) {
        plot.callsign = callsign_of(id);
      }
    }
    add(out, asterix::encode_cat048_record(plot));
  }
  return out;
}

ScanRecords broadcast_reports(const SimulatedScan& scan, const StationConfig& station,
                              asterix::DataSource source, double time_of_day_s,
                              const GeoAnchor& anchor) {
  ScanRecords out{asterix::kCat021, {}, 0};
  asterix::AdsbQuality quality;
  // The bounds an aircraft with the station's errors would broadcast: 95 % of a circular
  // error of σ per axis (asterix/quality.hpp), of the larger of east's and north's σ, so that
  // the bound holds on both.
  const auto& std_of = station.sensor.noise_std;
  quality.nacp = asterix::nacp_of_epu(asterix::kHorizontal95 * std::max(std_of(0), std_of(1)));
  quality.nucr_or_nacv =
      asterix::nacv_of_error(asterix::kHorizontal95 * std::max(std_of(3), std_of(4)));
  for (std::size_t j = 0; j < scan.scan.detections.size(); ++j) {
    const Detection& z = scan.scan.detections[j];
    asterix::AdsbReport report;
    report.source = source;
    report.simulated = true;
    report.time_of_applicability_s = time_of_day_s;
    report.time_of_reception_s = time_of_day_s;
    const Address address = address_of(scan.scan.addresses, j);
    if (address > 0xFFFFFFU) {
      ++out.left_out;
      continue;
    }
    report.address = address;
    report.address_type = address == kNoAddress ? 3 : 0;  // anonymous, or an ICAO address
    const Vector3 geodetic = from_local_enu(anchor, Vector3(z(0), z(1), z(2)));
    report.latitude_deg = geodetic.x();
    report.longitude_deg = geodetic.y();
    report.geometric_height_m = geodetic.z();
    report.quality = quality;
    report.ground_vector =
        asterix::GroundVector{std::hypot(z(3), z(4)), std::atan2(z(3), z(4)) * kDegPerRad};
    report.vertical_rate_mps = z(5);
    if (const Identification id = identification_at(scan.scan.identifications, j);
        id != kNoIdentification) {
      report.callsign = callsign_of(id);
    }
    add(out, asterix::encode_cat021_record(report));
  }
  return out;
}

}  // namespace

bool carried_by_asterix(std::string_view sensor_kind) {
  return sensor_kind == "range_azimuth" || sensor_kind == "range_azimuth_altitude" ||
         sensor_kind == "position_velocity";
}

std::optional<asterix::DataSource> station_source(const Scenario& scenario, int station_id) {
  if (station_id < 0 || station_id > 255) return std::nullopt;
  return asterix::DataSource{static_cast<std::uint8_t>(scenario.asterix.sac),
                             static_cast<std::uint8_t>(station_id)};
}

ScanRecords scan_records(const SimulatedScan& scan, const StationConfig& station,
                         double time_of_day_s, const Scenario& scenario) {
  if (!carried_by_asterix(scan.sensor_kind)) return {};
  const bool mode_s = scan.sensor_kind == "range_azimuth_altitude";
  const bool broadcast = scan.sensor_kind == "position_velocity";
  const auto source = station_source(scenario, station.id);
  if (!source) return {0, {}, scan.scan.detections.size()};
  if (broadcast) return broadcast_reports(scan, station, *source, time_of_day_s, scenario.anchor);
  return radar_plots(scan, *source, time_of_day_s, mode_s);
}

std::optional<Scan> scan_of_plots(int station_id, std::string_view sensor_kind,
                                  std::span<const asterix::RadarPlot> plots, std::size_t& skipped) {
  const bool mode_s = sensor_kind == "range_azimuth_altitude";
  if (!mode_s && sensor_kind != "range_azimuth") return std::nullopt;
  Scan scan;
  scan.station_id = station_id;
  for (const asterix::RadarPlot& plot : plots) {
    if (mode_s && !plot.flight_level) {
      ++skipped;
      continue;
    }
    Detection z(mode_s ? 3 : 2);
    z(0) = plot.range_m;
    z(1) = azimuth_rad(plot.azimuth_deg);
    if (mode_s) {
      z(2) = *plot.flight_level * 100.0 * kFootM;
      scan.addresses.push_back(plot.address.value_or(kNoAddress));
      scan.identifications.push_back(
          plot.callsign ? identification_of(*plot.callsign).value_or(kNoIdentification)
                        : kNoIdentification);
    }
    scan.detections.push_back(z);
  }
  drop_what_no_detection_has(scan);
  return scan;
}

std::optional<Scan> scan_of_reports(int station_id, std::span<const asterix::AdsbReport> reports,
                                    const GeoAnchor& anchor, std::size_t& skipped) {
  Scan scan;
  scan.station_id = station_id;
  for (const asterix::AdsbReport& report : reports) {
    if (!report.geometric_height_m || !report.ground_vector) {
      ++skipped;
      continue;
    }
    const Vector3 p =
        to_local_enu(anchor, report.latitude_deg, report.longitude_deg, *report.geometric_height_m);
    const double track_rad = report.ground_vector->track_angle_deg / kDegPerRad;
    const double speed = report.ground_vector->ground_speed_mps;
    Detection z(6);
    z << p.x(), p.y(), p.z(), speed * std::sin(track_rad), speed * std::cos(track_rad),
        report.vertical_rate_mps.value_or(0.0);
    scan.detections.push_back(z);
    scan.addresses.push_back(report.address_type == 3 ? kNoAddress : report.address);
    scan.identifications.push_back(
        report.callsign ? identification_of(*report.callsign).value_or(kNoIdentification)
                        : kNoIdentification);
    scan.reported_std.push_back(stated_std(report.quality));
  }
  drop_what_no_detection_has(scan);
  return scan;
}

std::optional<Scan> quantised_as_asterix(const SimulatedScan& scan, const StationConfig& station,
                                         const Scenario& scenario) {
  const GeoAnchor& anchor = scenario.anchor;
  const ScanRecords records = scan_records(scan, station, 0.0, scenario);
  if (records.category == 0) return std::nullopt;
  std::optional<asterix::EncodeError> error;
  const std::vector<asterix::Bytes> blocks =
      asterix::encode_blocks(records.category, records.records, asterix::kMaxUdpPayload, error);
  if (error) return std::nullopt;
  asterix::Decoded decoded;
  for (const asterix::Bytes& block : blocks) asterix::decode_datagram(block, decoded);
  std::size_t skipped = 0;
  std::optional<Scan> quantised =
      records.category == asterix::kCat021
          ? scan_of_reports(scan.scan.station_id, decoded.reports, anchor, skipped)
          : scan_of_plots(scan.scan.station_id, scan.sensor_kind, decoded.plots, skipped);
  if (quantised) quantised->noise = scan.scan.noise;
  return quantised;
}

}  // namespace skyfuse::transport
