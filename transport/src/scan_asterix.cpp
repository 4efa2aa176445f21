#include "report/scan_asterix.hpp"

#include <cmath>
#include <numbers>

#include "skyfuse/asterix/cat021.hpp"
#include "skyfuse/asterix/cat048.hpp"
#include "skyfuse/asterix/quality.hpp"
#include "skyfuse/picture/address.hpp"

namespace skyfuse::harness {
namespace {

constexpr double kFootM = 0.3048;
constexpr double kDegPerRad = 180.0 / std::numbers::pi;

// The scenario's azimuth (counter-clockwise from east) as ASTERIX's (clockwise from north).
double bearing_deg(double azimuth_rad) {
  return std::fmod(90.0 - azimuth_rad * kDegPerRad + 360.0, 360.0);
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
  // error of σ per axis (asterix/quality.hpp).
  quality.nacp = asterix::nacp_of_epu(asterix::kHorizontal95 * station.sensor.noise_std(0));
  quality.nucr_or_nacv =
      asterix::nacv_of_error(asterix::kHorizontal95 * station.sensor.noise_std(3));
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
    add(out, asterix::encode_cat021_record(report));
  }
  return out;
}

}  // namespace

ScanRecords scan_records(const SimulatedScan& scan, const StationConfig& station,
                         double time_of_day_s, const GeoAnchor& anchor) {
  const bool radar = scan.sensor_kind == "range_azimuth";
  const bool mode_s = scan.sensor_kind == "range_azimuth_altitude";
  const bool broadcast = scan.sensor_kind == "position_velocity";
  if (!radar && !mode_s && !broadcast) return {};
  if (station.id < 0 || station.id > 255) {
    return {0, {}, scan.scan.detections.size()};
  }
  const asterix::DataSource source{0, static_cast<std::uint8_t>(station.id)};
  if (broadcast) return broadcast_reports(scan, station, source, time_of_day_s, anchor);
  return radar_plots(scan, source, time_of_day_s, mode_s);
}

}  // namespace skyfuse::harness
