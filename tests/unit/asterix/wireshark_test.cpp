// The Wireshark check: a pcap of CAT062, CAT048 and CAT021 blocks as skyfuse writes them,
// decoded by tshark (Debian's Wireshark, whose ASTERIX dissector is independent of this code),
// must show no malformed packet and no expert information, as many records as were written,
// and every field equal to the value written within half of its item's LSB.
//
// Wireshark 4.0's defaults are the editions this library writes (CAT062 1.19, CAT048 1.31,
// CAT021 2.6). One difference is known and asserted as such: Wireshark 4.0 reads I048/090's
// flight level as unsigned, where the standard has it in two's complement, so a negative
// flight level shows there as FL + 4096 (the 14-bit pattern read unsigned).
//
// Skipped, saying so, where tshark is not installed (Debian: apt-get install tshark).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "skyfuse/asterix/cat021.hpp"
#include "skyfuse/asterix/cat048.hpp"
#include "skyfuse/asterix/cat062.hpp"
#include "skyfuse/asterix/pcap.hpp"
#include "skyfuse/asterix/units.hpp"

namespace skyfuse::asterix {
namespace {

using nlohmann::json;

constexpr std::uint16_t kPort = 8600;  // Wireshark's default port for ASTERIX over UDP
// tshark prints doubles with 15 significant digits; this covers that rounding.
constexpr double kPrinted = 1e-9;

std::optional<std::filesystem::path> find_tshark() {
  if (const char* path = std::getenv("PATH")) {
    std::stringstream dirs(path);
    for (std::string dir; std::getline(dirs, dir, ':');) {
      const auto candidate = std::filesystem::path(dir) / "tshark";
      if (!dir.empty() && std::filesystem::exists(candidate)) return candidate;
    }
  }
  return std::nullopt;
}

// ---- what is written: realistic values, both hemispheres' negative sides ----

std::vector<SystemTrack> tracks() {
  SystemTrack addressed;
  addressed.source = {25, 100};
  addressed.service_id = 3;
  addressed.track_number = 4242;
  addressed.time_of_track_s = 45296.5078125;
  addressed.x_m = -15234.7;
  addressed.y_m = 48211.3;
  addressed.latitude_deg = -34.822222;  // south of the equator, west of Greenwich
  addressed.longitude_deg = -58.535833;
  addressed.vx_mps = -120.3;
  addressed.vy_mps = 64.1;
  addressed.mode3a = 07123;
  addressed.address = 0xE80456;
  addressed.callsign = "KLM1023";
  addressed.geometric_altitude_m = 3352.8;
  addressed.status.altitude_source = 3;
  addressed.accuracy = TrackAccuracy{12.3, 7.4, -20.0, 1.1, 0.6, 30.0};

  SystemTrack unaddressed;
  unaddressed.source = {25, 100};
  unaddressed.service_id = 3;
  unaddressed.track_number = 7;
  unaddressed.time_of_track_s = 45297.0;
  unaddressed.x_m = 250000.25;
  unaddressed.y_m = -310000.75;
  unaddressed.latitude_deg = 51.4775;
  unaddressed.longitude_deg = -0.461389;
  unaddressed.vx_mps = 0.0;
  unaddressed.vy_mps = -250.0;
  unaddressed.status.tentative = true;
  unaddressed.status.mono_sensor = true;
  unaddressed.accuracy = TrackAccuracy{150.0, 150.0, 900.0, 10.0, 10.0, std::nullopt};

  SystemTrack coasting = addressed;
  coasting.track_number = 65535;
  coasting.time_of_track_s = 86399.9921875;
  coasting.latitude_deg = -89.5;
  coasting.longitude_deg = 179.999;
  coasting.address = 0x000001;
  coasting.mode3a = 07700;
  coasting.status = TrackStatus{};
  coasting.status.coasting = true;
  coasting.geometric_altitude_m = -150.0;
  coasting.accuracy.reset();
  return {addressed, unaddressed, coasting};
}

std::vector<RadarPlot> plots() {
  RadarPlot mode_s;
  mode_s.source = {25, 10};
  mode_s.time_of_day_s = 45296.25;
  mode_s.range_m = 185200.0 * 0.4321;
  mode_s.azimuth_deg = 271.3;
  mode_s.mode3a = 01234;
  mode_s.flight_level = 350.25;
  mode_s.address = 0x3C6586;
  mode_s.callsign = "BAW123";
  mode_s.track_number = 3000;

  RadarPlot primary;
  primary.source = {25, 10};
  primary.time_of_day_s = 45296.3;
  primary.detection = DetectionType::psr;
  primary.range_m = 1852.0 * 255.9;
  primary.azimuth_deg = -0.01;  // just west of north: 359.99°

  RadarPlot low;  // below the pressure datum: a negative flight level
  low.source = {25, 10};
  low.time_of_day_s = 45296.4;
  low.detection = DetectionType::ssr_psr;
  low.simulated = true;
  low.test_target = true;
  low.range_m = 3000.0;
  low.azimuth_deg = 45.0;
  low.mode3a = 07000;
  low.flight_level = -5.25;
  return {mode_s, primary, low};
}

std::vector<AdsbReport> reports() {
  AdsbReport high;
  high.source = {25, 11};
  high.time_of_applicability_s = 45296.5;
  high.time_of_reception_s = 45296.6;
  high.address = 0xA1B2C3;
  high.latitude_deg = -33.946111;
  high.longitude_deg = 151.177222;
  high.geometric_height_m = 10668.0;
  high.quality = AdsbQuality{2, 8, 1, 3, 9, 0, 2, 1};
  high.ground_vector = GroundVector{231.5, 271.2};
  high.vertical_rate_mps = -7.62;  // 1 500 ft/min descending
  high.callsign = "QFA1";

  AdsbReport low = high;
  low.address = 0x4CA2B3;
  low.address_type = 3;
  low.altitude_reporting = 1;
  low.latitude_deg = 40.639722;
  low.longitude_deg = -73.778889;
  low.position_items = PositionItems::low_resolution;
  low.geometric_height_m.reset();
  low.ground_vector.reset();
  low.vertical_rate_mps.reset();
  low.callsign.reset();

  AdsbReport ground = high;
  ground.address = 0x800123;
  ground.ground = true;
  ground.position_items = PositionItems::both;
  ground.latitude_deg = -22.8099;
  ground.longitude_deg = -43.2506;
  ground.geometric_height_m = -30.0;
  ground.ground_vector = GroundVector{8.2, 359.99};
  ground.vertical_rate_mps = 0.0;
  return {high, low, ground};
}

// ---- reading tshark's JSON ----

// A key tshark writes once as an object, several times (--no-duplicate-keys) as an array.
std::vector<json> as_list(const json& value) {
  if (value.is_array()) return value.get<std::vector<json>>();
  return {value};
}

std::string text(const json& record, const std::string& item, const std::string& field) {
  return record.at(item).at(field).get<std::string>();
}

// A callsign as the item carries it: padded with spaces to its 8 characters.
std::string padded(std::string callsign) {
  callsign.resize(8, ' ');
  return callsign;
}

double number(const json& record, const std::string& item, const std::string& field) {
  const auto& value = record.at(item).at(field);
  const auto text = value.get<std::string>();
  return text.rfind("0x", 0) == 0 ? static_cast<double>(std::stoul(text, nullptr, 16))
                                  : std::stod(text);
}

bool contains_key(const json& value, const std::string& prefix) {
  if (value.is_object()) {
    for (const auto& [key, child] : value.items()) {
      if (key.rfind(prefix, 0) == 0 || contains_key(child, prefix)) return true;
    }
  } else if (value.is_array()) {
    for (const auto& child : value) {
      if (contains_key(child, prefix)) return true;
    }
  }
  return false;
}

// Two angles in degrees, as the shorter way round.
double angle_gap(double a, double b) {
  return std::fabs(std::remainder(a - b, 360.0));
}

void check_track(const json& r, const SystemTrack& t) {
  SCOPED_TRACE(::testing::Message() << "CAT062 track " << t.track_number);
  EXPECT_EQ(number(r, "asterix.062_010", "asterix.062_010_SAC"), t.source.sac);
  EXPECT_EQ(number(r, "asterix.062_010", "asterix.062_010_SIC"), t.source.sic);
  EXPECT_EQ(number(r, "asterix.062_015", "asterix.062_015_VALUE"), t.service_id);
  EXPECT_EQ(number(r, "asterix.062_040", "asterix.062_040_VALUE"), t.track_number);
  EXPECT_NEAR(number(r, "asterix.062_070", "asterix.062_070_VALUE"), t.time_of_track_s,
              1.0 / 256 + kPrinted);
  const double half_wgs84 = 180.0 / std::ldexp(1.0, 26);
  EXPECT_NEAR(number(r, "asterix.062_105", "asterix.062_105_LAT"), t.latitude_deg,
              half_wgs84 + kPrinted);
  EXPECT_LE(angle_gap(number(r, "asterix.062_105", "asterix.062_105_LON"), t.longitude_deg),
            half_wgs84 + kPrinted);
  EXPECT_NEAR(number(r, "asterix.062_100", "asterix.062_100_X"), t.x_m, 0.25 + kPrinted);
  EXPECT_NEAR(number(r, "asterix.062_100", "asterix.062_100_Y"), t.y_m, 0.25 + kPrinted);
  EXPECT_NEAR(number(r, "asterix.062_185", "asterix.062_185_VX"), t.vx_mps, 0.125 + kPrinted);
  EXPECT_NEAR(number(r, "asterix.062_185", "asterix.062_185_VY"), t.vy_mps, 0.125 + kPrinted);
  EXPECT_EQ(number(r, "asterix.062_080", "asterix.062_080_MON"), t.status.mono_sensor ? 1 : 0);
  EXPECT_EQ(number(r, "asterix.062_080", "asterix.062_080_CNF"), t.status.tentative ? 1 : 0);
  EXPECT_EQ(number(r, "asterix.062_080", "asterix.062_080_SRC"), t.status.altitude_source);
  if (t.status.coasting) {
    EXPECT_EQ(number(r, "asterix.062_080", "asterix.062_080_CST"), 1);
  }
  ASSERT_EQ(r.contains("asterix.062_060"), t.mode3a.has_value());
  if (t.mode3a) {
    EXPECT_EQ(number(r, "asterix.062_060", "asterix.062_060_MODE3A"), *t.mode3a);
  }
  ASSERT_EQ(r.contains("asterix.062_245"), t.callsign.has_value());
  if (t.callsign) {
    EXPECT_EQ(number(r, "asterix.062_245", "asterix.062_245_STI"), 0);  // downlinked
    EXPECT_EQ(padded(*t.callsign), text(r, "asterix.062_245", "asterix.062_245_CHR"));
  }
  ASSERT_EQ(r.contains("asterix.062_380"), t.address.has_value());
  if (t.address) {
    EXPECT_EQ(number(r.at("asterix.062_380"), "asterix.062_380_ADR", "asterix.062_380_ADR_VALUE"),
              *t.address);
  }
  ASSERT_EQ(r.contains("asterix.062_130"), t.geometric_altitude_m.has_value());
  if (t.geometric_altitude_m) {
    EXPECT_NEAR(number(r, "asterix.062_130", "asterix.062_130_VALUE"),
                *t.geometric_altitude_m / kMetresPerFoot, 3.125 + kPrinted);
  }
  ASSERT_EQ(r.contains("asterix.062_500"), t.accuracy.has_value());
  if (t.accuracy) {
    const auto& a = r.at("asterix.062_500");
    EXPECT_NEAR(number(a, "asterix.062_500_APC", "asterix.062_500_APC_X"), t.accuracy->sigma_x_m,
                0.25 + kPrinted);
    EXPECT_NEAR(number(a, "asterix.062_500_APC", "asterix.062_500_APC_Y"), t.accuracy->sigma_y_m,
                0.25 + kPrinted);
    const double cov = t.accuracy->covariance_xy_m2;
    EXPECT_NEAR(number(a, "asterix.062_500_COV", "asterix.062_500_COV_VALUE"),
                std::copysign(std::sqrt(std::fabs(cov)), cov), 0.25 + kPrinted);
    EXPECT_NEAR(number(a, "asterix.062_500_ATV", "asterix.062_500_ATV_X"), t.accuracy->sigma_vx_mps,
                0.125 + kPrinted);
    EXPECT_NEAR(number(a, "asterix.062_500_ATV", "asterix.062_500_ATV_Y"), t.accuracy->sigma_vy_mps,
                0.125 + kPrinted);
    if (t.accuracy->sigma_altitude_m) {
      EXPECT_NEAR(number(a, "asterix.062_500_AGA", "asterix.062_500_AGA_VALUE"),
                  *t.accuracy->sigma_altitude_m / kMetresPerFoot, 3.125 + kPrinted);
    }
  }
}

void check_plot(const json& r, const RadarPlot& p) {
  SCOPED_TRACE(::testing::Message() << "CAT048 plot at " << p.time_of_day_s << " s");
  EXPECT_EQ(number(r, "asterix.048_010", "asterix.048_010_SAC"), p.source.sac);
  EXPECT_EQ(number(r, "asterix.048_010", "asterix.048_010_SIC"), p.source.sic);
  EXPECT_NEAR(number(r, "asterix.048_140", "asterix.048_140_VALUE"), p.time_of_day_s,
              1.0 / 256 + kPrinted);
  EXPECT_EQ(number(r, "asterix.048_020", "asterix.048_020_TYP"), static_cast<int>(p.detection));
  EXPECT_EQ(number(r, "asterix.048_020", "asterix.048_020_SIM"), p.simulated ? 1 : 0);
  if (p.test_target) {
    EXPECT_EQ(number(r, "asterix.048_020", "asterix.048_020_TST"), 1);
  }
  EXPECT_NEAR(number(r, "asterix.048_040", "asterix.048_040_RHO"),
              p.range_m / kMetresPerNauticalMile, 1.0 / 512 + kPrinted);
  EXPECT_LE(angle_gap(number(r, "asterix.048_040", "asterix.048_040_THETA"), p.azimuth_deg),
            180.0 / 65536 + kPrinted);
  ASSERT_EQ(r.contains("asterix.048_070"), p.mode3a.has_value());
  if (p.mode3a) {
    EXPECT_EQ(number(r, "asterix.048_070", "asterix.048_070_MODE3A"), *p.mode3a);
  }
  ASSERT_EQ(r.contains("asterix.048_090"), p.flight_level.has_value());
  if (p.flight_level) {
    const double shown = number(r, "asterix.048_090", "asterix.048_090_FL");
    // Wireshark 4.0 reads the 14-bit two's complement field unsigned (see the top of the file).
    const double expected = *p.flight_level < 0 ? *p.flight_level + 4096 : *p.flight_level;
    EXPECT_NEAR(shown, expected, 0.125 + kPrinted);
  }
  ASSERT_EQ(r.contains("asterix.048_240"), p.callsign.has_value());
  if (p.callsign) {
    EXPECT_EQ(padded(*p.callsign), text(r, "asterix.048_240", "asterix.048_240_VALUE"));
  }
  ASSERT_EQ(r.contains("asterix.048_220"), p.address.has_value());
  if (p.address) {
    EXPECT_EQ(number(r, "asterix.048_220", "asterix.048_220_VALUE"), *p.address);
  }
  ASSERT_EQ(r.contains("asterix.048_161"), p.track_number.has_value());
  if (p.track_number) {
    EXPECT_EQ(number(r, "asterix.048_161", "asterix.048_161_TRN"), *p.track_number);
  }
}

void check_report(const json& r, const AdsbReport& a) {
  SCOPED_TRACE(::testing::Message() << "CAT021 report of " << a.address);
  EXPECT_EQ(number(r, "asterix.021_010", "asterix.021_010_SAC"), a.source.sac);
  EXPECT_EQ(number(r, "asterix.021_010", "asterix.021_010_SIC"), a.source.sic);
  EXPECT_EQ(number(r, "asterix.021_040", "asterix.021_040_ATP"), a.address_type);
  EXPECT_EQ(number(r, "asterix.021_040", "asterix.021_040_ARC"), a.altitude_reporting);
  EXPECT_EQ(number(r, "asterix.021_040", "asterix.021_040_GBS"), a.ground ? 1 : 0);
  EXPECT_EQ(number(r, "asterix.021_040", "asterix.021_040_SIM"), a.simulated ? 1 : 0);
  EXPECT_EQ(number(r, "asterix.021_040", "asterix.021_040_TST"), a.test_target ? 1 : 0);
  EXPECT_NEAR(number(r, "asterix.021_071", "asterix.021_071_VALUE"), a.time_of_applicability_s,
              1.0 / 256 + kPrinted);
  EXPECT_NEAR(number(r, "asterix.021_073", "asterix.021_073_VALUE"), a.time_of_reception_s,
              1.0 / 256 + kPrinted);
  EXPECT_EQ(number(r, "asterix.021_080", "asterix.021_080_VALUE"), a.address);
  ASSERT_EQ(r.contains("asterix.021_170"), a.callsign.has_value());
  if (a.callsign) {
    EXPECT_EQ(padded(*a.callsign), text(r, "asterix.021_170", "asterix.021_170_VALUE"));
  }
  const bool low = a.position_items != PositionItems::high_resolution;
  const bool high = a.position_items != PositionItems::low_resolution;
  ASSERT_EQ(r.contains("asterix.021_130"), low);
  ASSERT_EQ(r.contains("asterix.021_131"), high);
  if (low) {
    const double half = 180.0 / std::ldexp(1.0, 24);
    EXPECT_NEAR(number(r, "asterix.021_130", "asterix.021_130_LAT"), a.latitude_deg,
                half + kPrinted);
    EXPECT_NEAR(number(r, "asterix.021_130", "asterix.021_130_LON"), a.longitude_deg,
                half + kPrinted);
  }
  if (high) {
    const double half = 180.0 / std::ldexp(1.0, 31);
    EXPECT_NEAR(number(r, "asterix.021_131", "asterix.021_131_LAT"), a.latitude_deg,
                half + kPrinted);
    EXPECT_NEAR(number(r, "asterix.021_131", "asterix.021_131_LON"), a.longitude_deg,
                half + kPrinted);
  }
  ASSERT_EQ(r.contains("asterix.021_140"), a.geometric_height_m.has_value());
  if (a.geometric_height_m) {
    EXPECT_NEAR(number(r, "asterix.021_140", "asterix.021_140_VALUE"),
                *a.geometric_height_m / kMetresPerFoot, 3.125 + kPrinted);
  }
  const char* q = "asterix.021_090";
  EXPECT_EQ(number(r, q, "asterix.021_090_NUCRNACV"), a.quality.nucr_or_nacv);
  EXPECT_EQ(number(r, q, "asterix.021_090_NUCPNIC"), a.quality.nucp_or_nic);
  EXPECT_EQ(number(r, q, "asterix.021_090_NICBARO"), a.quality.nic_baro);
  EXPECT_EQ(number(r, q, "asterix.021_090_SIL"), a.quality.sil);
  EXPECT_EQ(number(r, q, "asterix.021_090_NACP"), a.quality.nacp);
  EXPECT_EQ(number(r, q, "asterix.021_090_SILS"), a.quality.sil_supplement);
  EXPECT_EQ(number(r, q, "asterix.021_090_SDA"), a.quality.sda);
  EXPECT_EQ(number(r, q, "asterix.021_090_GVA"), a.quality.gva);
  ASSERT_EQ(r.contains("asterix.021_157"), a.vertical_rate_mps.has_value());
  if (a.vertical_rate_mps) {
    EXPECT_EQ(number(r, "asterix.021_157", "asterix.021_157_RE"), 0);
    EXPECT_NEAR(number(r, "asterix.021_157", "asterix.021_157_GVR"),
                *a.vertical_rate_mps / kMetresPerFoot * 60.0, 3.125 + kPrinted);
  }
  ASSERT_EQ(r.contains("asterix.021_160"), a.ground_vector.has_value());
  if (a.ground_vector) {
    EXPECT_EQ(number(r, "asterix.021_160", "asterix.021_160_RE"), 0);
    EXPECT_NEAR(number(r, "asterix.021_160", "asterix.021_160_GS"),
                a.ground_vector->ground_speed_mps / kMetresPerNauticalMile,
                std::ldexp(1.0, -15) + kPrinted);
    EXPECT_LE(angle_gap(number(r, "asterix.021_160", "asterix.021_160_TA"),
                        a.ground_vector->track_angle_deg),
              180.0 / 65536 + kPrinted);
  }
}

Bytes concat(std::initializer_list<Bytes> parts) {
  Bytes all;
  for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
  return all;
}

TEST(AsterixWireshark, TsharkDecodesEveryFieldAsWritten) {
  const auto tshark = find_tshark();
  if (!tshark) {
    GTEST_SKIP() << "tshark is not installed (Debian: apt-get install tshark): the Wireshark "
                    "check of the ASTERIX encoders did not run";
  }
  const auto dir = std::filesystem::temp_directory_path() / "skyfuse_asterix_wireshark";
  std::filesystem::create_directories(dir);
  const auto pcap_path = dir / "asterix.pcap";

  const auto t = tracks();
  const auto p = plots();
  const auto a = reports();
  const auto cat062 = encode_cat062(t);
  const auto cat048 = encode_cat048(p);
  const auto cat021 = encode_cat021(a);
  ASSERT_TRUE(cat062 && cat048 && cat021);
  {
    PcapWriter writer(pcap_path);
    UdpDatagram d;
    d.time_ns = 1'717'200'000'000'000'000;  // 2024-06-01 00:00:00 UTC
    d.source = {{10, 0, 0, 1}, 40000};
    d.destination = {{239, 62, 0, 1}, kPort};
    // One block per datagram, then one datagram holding all three blocks.
    for (const auto* block : {&cat062.bytes, &cat048.bytes, &cat021.bytes}) {
      d.payload = *block;
      writer.write(d);
      d.time_ns += 1'000'000;
    }
    d.payload = concat({cat062.bytes, cat048.bytes, cat021.bytes});
    writer.write(d);
    writer.close();
  }

  const auto out = dir / "tshark.json";
  const auto err = dir / "tshark.err";
  std::ostringstream command;
  command << "'" << tshark->string() << "' -r '" << pcap_path.string() << "' -d udp.port==" << kPort
          << ",asterix -T json --no-duplicate-keys > '" << out.string() << "' 2> '" << err.string()
          << "'";
  ASSERT_EQ(std::system(command.str().c_str()), 0) << command.str() << " failed; see " << err;
  std::ifstream in(out);
  const auto packets = json::parse(in);
  ASSERT_EQ(packets.size(), 4u);

  std::vector<json> records062, records048, records021;
  for (const auto& packet : packets) {
    const auto& layers = packet.at("_source").at("layers");
    EXPECT_FALSE(contains_key(layers, "_ws.malformed")) << layers.dump();
    EXPECT_FALSE(contains_key(layers, "_ws.expert")) << layers.dump();
    ASSERT_TRUE(layers.contains("asterix")) << layers.dump();
    for (const auto& block : as_list(layers.at("asterix"))) {
      const auto category = block.at("asterix.category").get<std::string>();
      auto& into = category == "62" ? records062 : category == "48" ? records048 : records021;
      for (const auto& record : as_list(block.at("asterix.message"))) into.push_back(record);
    }
  }
  ASSERT_EQ(records062.size(), 2 * t.size());
  ASSERT_EQ(records048.size(), 2 * p.size());
  ASSERT_EQ(records021.size(), 2 * a.size());
  for (std::size_t i = 0; i < records062.size(); ++i) check_track(records062[i], t[i % t.size()]);
  for (std::size_t i = 0; i < records048.size(); ++i) check_plot(records048[i], p[i % p.size()]);
  for (std::size_t i = 0; i < records021.size(); ++i) check_report(records021[i], a[i % a.size()]);
}

}  // namespace
}  // namespace skyfuse::asterix
