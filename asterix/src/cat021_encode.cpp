// CAT021 ed. 2.6 items, written in UAP order (cat021.hpp lists them with their resolutions).
#include <cmath>
#include <string>

#include "identification.hpp"
#include "item_fields.hpp"
#include "record_builder.hpp"
#include "skyfuse/asterix/cat021.hpp"
#include "skyfuse/asterix/units.hpp"

namespace skyfuse::asterix {
namespace {

// A raw code of `bits` bits, refused when wider.
std::uint32_t code(ByteWriter& out, std::string_view item, std::uint32_t value, unsigned bits) {
  if (value >= (1u << bits)) {
    out.fail(item,
             "code " + std::to_string(value) + " is wider than " + std::to_string(bits) + " bits");
    return 0;
  }
  return value;
}

// I021/040: primary ATP (8-6), ARC (5-4), RC (3) = 0, RAB (2) = 0, FX = 1; first extension
// DCR (8) = 0, GBS (7), SIM (6), TST (5), SAA (4) = 0, CL (3-2) = 0 (report valid), FX = 0.
void put_descriptor(ByteWriter& out, const AdsbReport& r) {
  if (r.address_type > 3) out.fail("I021/040 ATP", "address types 4-7 are reserved");
  const auto atp = code(out, "I021/040 ATP", r.address_type, 3);
  const auto arc = code(out, "I021/040 ARC", r.altitude_reporting, 2);
  out.put(atp << 5 | arc << 3 | 0x01u, 1);
  out.put((r.ground ? 0x40u : 0u) | (r.simulated ? 0x20u : 0u) | (r.test_target ? 0x10u : 0u), 1);
}

// I021/090: primary NUCr/NACv (8-6), NUCp/NIC (5-2); first extension NICbaro (8), SIL (7-6),
// NACp (5-2); second extension spare (8-7), SIL-supplement (6), SDA (5-4), GVA (3-2).
void put_quality(ByteWriter& out, const AdsbQuality& q) {
  const auto nacv = code(out, "I021/090 NUCr/NACv", q.nucr_or_nacv, 3);
  const auto nic = code(out, "I021/090 NUCp/NIC", q.nucp_or_nic, 4);
  const auto nic_baro = code(out, "I021/090 NICbaro", q.nic_baro, 1);
  const auto sil = code(out, "I021/090 SIL", q.sil, 2);
  const auto nacp = code(out, "I021/090 NACp", q.nacp, 4);
  const auto sils = code(out, "I021/090 SILS", q.sil_supplement, 1);
  const auto sda = code(out, "I021/090 SDA", q.sda, 2);
  const auto gva = code(out, "I021/090 GVA", q.gva, 2);
  out.put(nacv << 5 | nic << 1 | 0x01u, 1);
  out.put(nic_baro << 7 | sil << 5 | nacp << 1 | 0x01u, 1);
  out.put(sils << 5 | sda << 3 | gva << 1, 1);
}

// I021/157: RE (bit 16) = 0, the geometric vertical rate in 15 bits of two's complement,
// 6.25 ft/min each.
void put_vertical_rate(ByteWriter& out, double rate_mps) {
  const double feet_per_minute = rate_mps / kMetresPerFoot * 60.0;
  const auto count = quantise(feet_per_minute, 6.25, 15, Signedness::twos_complement);
  if (!count) {
    out.fail("I021/157 GVR",
             "vertical rate " + std::to_string(rate_mps) + " m/s is not within ±102 400 ft/min");
  }
  out.put(field_bits(count.value_or(0), 15), 2);
}

// I021/160: RE (bit 32) = 0, ground speed in 15 bits of 2^-14 NM/s (below 2 NM/s), track
// angle in 16 bits of 360/2^16 deg.
void put_ground_vector(ByteWriter& out, const GroundVector& v) {
  const auto speed = quantise(v.ground_speed_mps / kMetresPerNauticalMile, std::ldexp(1.0, -14), 15,
                              Signedness::unsigned_field);
  if (!speed) {
    out.fail("I021/160 GS",
             "ground speed " + std::to_string(v.ground_speed_mps) + " m/s is not in [0, 2 NM/s)");
  }
  out.put(static_cast<std::uint32_t>(speed.value_or(0)), 2);
  fields::put_angle16(out, v.track_angle_deg);
}

}  // namespace

Encoded encode_cat021_record(const AdsbReport& r) {
  RecordBuilder record(uap_cat021());

  fields::put_data_source(record.item(10), r.source);

  put_descriptor(record.item(40), r);

  fields::put_time_of_day(record.item(71), "I021/071", r.time_of_applicability_s);

  if (r.position_items != PositionItems::high_resolution) {
    auto& i130 = record.item(130);  // 24 bits each, LSB 180/2^23 deg (about 2.4 m)
    fields::put_latitude(i130, "I021/130 LAT", r.latitude_deg, 24, 23);
    fields::put_longitude(i130, "I021/130 LON", r.longitude_deg, 24, 23);
  }
  if (r.position_items != PositionItems::low_resolution) {
    auto& i131 = record.item(131);  // 32 bits each, LSB 180/2^30 deg (about 2 cm)
    fields::put_latitude(i131, "I021/131 LAT", r.latitude_deg, 32, 30);
    fields::put_longitude(i131, "I021/131 LON", r.longitude_deg, 32, 30);
  }

  fields::put_address(record.item(80), "I021/080", r.address);

  fields::put_time_of_day(record.item(73), "I021/073", r.time_of_reception_s);

  if (r.geometric_height_m) {
    // The standard's range is [-1500, 150000) ft; all ones (0x7FFF) would mean "greater than".
    fields::put_bounded(record.item(140), "I021/140", *r.geometric_height_m / kMetresPerFoot,
                        -1500.0, 150000.0 - 6.25, 6.25, 2, Signedness::twos_complement);
  }

  put_quality(record.item(90), r.quality);

  if (r.vertical_rate_mps) put_vertical_rate(record.item(157), *r.vertical_rate_mps);

  if (r.ground_vector) put_ground_vector(record.item(160), *r.ground_vector);

  if (r.callsign) fields::put_identification(record.item(170), "I021/170", *r.callsign);

  return std::move(record).finish();
}

Encoded encode_cat021(std::span<const AdsbReport> reports) {
  return encode_block_of(kCat021, reports, encode_cat021_record);
}

}  // namespace skyfuse::asterix
