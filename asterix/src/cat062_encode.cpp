// CAT062 ed. 1.19 items, written in UAP order (cat062.hpp lists them with their resolutions).
#include <cmath>

#include "identification.hpp"
#include "item_fields.hpp"
#include "record_builder.hpp"
#include "skyfuse/asterix/cat062.hpp"
#include "skyfuse/asterix/units.hpp"

namespace skyfuse::asterix {
namespace {

constexpr unsigned kWgs84Scale = 25;  // I062/105: LSB 180/2^25 deg, about 0.6 m of latitude

std::uint8_t bit(bool set, unsigned position) {
  return set ? static_cast<std::uint8_t>(1u << (position - 1)) : 0;
}

// I062/080: the primary octet always, then extensions up to the last one with a flag set
// (FX, bit 1, set on every octet but the last). Octet 3 (AMA, Mode 4/5) carries nothing here
// and is sent as zeros when octet 4 (the ages) is needed.
void put_track_status(ByteWriter& out, const TrackStatus& s, bool geometric_altitude) {
  std::uint8_t octets[4] = {
      static_cast<std::uint8_t>(bit(s.mono_sensor, 8) | bit(geometric_altitude, 6) |
                                (s.altitude_source & 0x7u) << 2 | bit(s.tentative, 2)),
      static_cast<std::uint8_t>(bit(s.simulated, 8) | bit(s.last_message, 7) |
                                bit(s.first_message, 6)),
      0,
      static_cast<std::uint8_t>(bit(s.coasting, 8) | bit(s.psr_aged, 7) | bit(s.ssr_aged, 6) |
                                bit(s.mode_s_aged, 5) | bit(s.adsb_aged, 4))};
  if (s.altitude_source > 7) out.fail("I062/080 SRC", "altitude source above 7");
  std::size_t count = octets[3] != 0 ? 4 : octets[1] != 0 ? 2 : 1;
  for (std::size_t i = 0; i < count; ++i) {
    out.put(octets[i] | (i + 1 < count ? 0x01u : 0x00u), 1);
  }
}

// I062/500: APC, COV, ATV and (if given) AGA. "Maximum value means maximum value or above"
// (the standard's notes), so these clamp instead of refusing.
void put_accuracy(ByteWriter& out, const TrackAccuracy& a) {
  const unsigned present[] = {1, 2, 6, a.sigma_altitude_m ? 4u : 0u};
  Bytes primary;
  append_fspec(primary, present);
  for (const auto octet : primary) out.put(octet, 1);

  const auto clamped = [&out](std::string_view item, double value, double lsb, unsigned bits) {
    const auto count = quantise_clamped(value, lsb, bits);
    if (!count) out.fail(item, "a standard deviation must be finite and not negative");
    out.put(count ? static_cast<std::uint32_t>(*count) : 0, bits / 8);
  };
  clamped("I062/500 APC X", a.sigma_x_m, 0.5, 16);
  clamped("I062/500 APC Y", a.sigma_y_m, 0.5, 16);

  // COV: sign(cov)·sqrt(|cov|) in 0.5 m, two's complement, magnitude up to 32767 LSB.
  if (!std::isfinite(a.covariance_xy_m2)) out.fail("I062/500 COV", "not finite");
  const double root = std::sqrt(std::fabs(a.covariance_xy_m2));
  const auto magnitude = quantise_clamped(std::isfinite(root) ? root : 0.0, 0.5, 15);
  const std::int64_t cov = (a.covariance_xy_m2 < 0 ? -1 : 1) * magnitude.value_or(0);
  out.put(field_bits(cov, 16), 2);

  if (a.sigma_altitude_m) {
    clamped("I062/500 AGA", *a.sigma_altitude_m / kMetresPerFoot, 6.25, 8);
  }
  clamped("I062/500 ATV X", a.sigma_vx_mps, 0.25, 8);
  clamped("I062/500 ATV Y", a.sigma_vy_mps, 0.25, 8);
}

}  // namespace

Encoded encode_cat062_record(const SystemTrack& t) {
  RecordBuilder record(uap_cat062());

  fields::put_data_source(record.item(10), t.source);

  record.item(15).put(t.service_id, 1);

  fields::put_time_of_day(record.item(70), "I062/070", t.time_of_track_s);

  auto& i105 = record.item(105);
  fields::put_latitude(i105, "I062/105 LAT", t.latitude_deg, 32, kWgs84Scale);
  fields::put_longitude(i105, "I062/105 LON", t.longitude_deg, 32, kWgs84Scale);

  auto& i100 = record.item(100);  // 24 bits each: ±4 194 304 m
  i100.put_quantity("I062/100 X", t.x_m, 0.5, 3, Signedness::twos_complement);
  i100.put_quantity("I062/100 Y", t.y_m, 0.5, 3, Signedness::twos_complement);

  auto& i185 = record.item(185);  // 16 bits each: [-8192, 8191.75] m/s
  i185.put_quantity("I062/185 VX", t.vx_mps, 0.25, 2, Signedness::twos_complement);
  i185.put_quantity("I062/185 VY", t.vy_mps, 0.25, 2, Signedness::twos_complement);

  if (t.mode3a) fields::put_mode3a(record.item(60), "I062/060", *t.mode3a);

  if (t.callsign) {
    auto& i245 = record.item(245);
    i245.put(0x00, 1);  // STI 0: downlinked from the target; spare bits 0
    fields::put_identification(i245, "I062/245", *t.callsign);
  }

  if (t.address) {
    auto& i380 = record.item(380);
    i380.put(0x80, 1);  // primary subfield: ADR (#1) alone, no FX
    fields::put_address(i380, "I062/380 ADR", *t.address);
  }

  record.item(40).put(t.track_number, 2);

  put_track_status(record.item(80), t.status, t.geometric_altitude_m.has_value());

  if (t.geometric_altitude_m) {
    fields::put_bounded(record.item(130), "I062/130", *t.geometric_altitude_m / kMetresPerFoot,
                        -1500.0, 150000.0, 6.25, 2, Signedness::twos_complement);
  }

  if (t.accuracy) put_accuracy(record.item(500), *t.accuracy);

  return std::move(record).finish();
}

Encoded encode_cat062(std::span<const SystemTrack> tracks) {
  return encode_block_of(kCat062, tracks, encode_cat062_record);
}

}  // namespace skyfuse::asterix
