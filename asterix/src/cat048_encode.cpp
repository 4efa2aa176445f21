// CAT048 ed. 1.31 items, written in UAP order (cat048.hpp lists them with their resolutions).
#include <string>

#include "identification.hpp"
#include "item_fields.hpp"
#include "record_builder.hpp"
#include "skyfuse/asterix/cat048.hpp"
#include "skyfuse/asterix/units.hpp"

namespace skyfuse::asterix {

Encoded encode_cat048_record(const RadarPlot& p) {
  RecordBuilder record(uap_cat048());

  fields::put_data_source(record.item(10), p.source);

  fields::put_time_of_day(record.item(140), "I048/140", p.time_of_day_s);

  // I048/020: TYP (bits 8-6), SIM (5), RDP (4) = chain 1, SPI (3), RAB (2) = aircraft, FX (1);
  // the first extension only for TST (its bit 8), with ERR, XPP, ME, MI, FOE/FRI all 0.
  auto& i020 = record.item(20);
  const auto typ = static_cast<std::uint32_t>(p.detection);
  if (typ > 7) i020.fail("I048/020 TYP", "detection type above 7");
  i020.put((typ & 0x7u) << 5 | (p.simulated ? 0x10u : 0u) | (p.test_target ? 0x01u : 0u), 1);
  if (p.test_target) i020.put(0x80, 1);

  // I048/040: RHO in 1/256 NM below 256 NM, THETA in 360/2^16 deg.
  auto& i040 = record.item(40);
  i040.put_quantity("I048/040 RHO", p.range_m / kMetresPerNauticalMile, 1.0 / 256.0, 2,
                    Signedness::unsigned_field);
  fields::put_angle16(i040, p.azimuth_deg);

  if (p.mode3a) fields::put_mode3a(record.item(70), "I048/070", *p.mode3a);

  // I048/090: V (16) = validated, G (15) = not garbled, then FL in 14 bits two's complement,
  // LSB 1/4 FL.
  if (p.flight_level) {
    auto& i090 = record.item(90);
    const auto count = quantise(*p.flight_level, 0.25, 14, Signedness::twos_complement);
    if (!count) {
      i090.fail("I048/090", "flight level " + std::to_string(*p.flight_level) +
                                " does not fit 14 bits of 1/4 FL");
    }
    i090.put(field_bits(count.value_or(0), 14), 2);
  }

  if (p.address) fields::put_address(record.item(220), "I048/220", *p.address);

  if (p.callsign) fields::put_identification(record.item(240), "I048/240", *p.callsign);

  // I048/161: 4 spare bits, then the track number in 12 bits.
  if (p.track_number) {
    auto& i161 = record.item(161);
    if (*p.track_number > 0x0FFFu) i161.fail("I048/161", "track number wider than 12 bits");
    i161.put(*p.track_number & 0x0FFFu, 2);
  }

  return std::move(record).finish();
}

Encoded encode_cat048(std::span<const RadarPlot> plots) {
  return encode_block_of(kCat048, plots, encode_cat048_record);
}

}  // namespace skyfuse::asterix
