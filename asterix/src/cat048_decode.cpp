// CAT048 ed. 1.31: the items encode_cat048_record writes, read back from a walked record.
#include "identification.hpp"
#include "item_fields.hpp"
#include "skyfuse/asterix/byte_reader.hpp"
#include "skyfuse/asterix/cat048.hpp"
#include "skyfuse/asterix/units.hpp"

namespace skyfuse::asterix {

Cat048Decoded decode_cat048_record(const WalkedRecord& record) {
  if (!has_items(record, {10, 140, 20, 40})) return {std::nullopt, Refusal::missing_item};
  RadarPlot p;
  for (const auto& item : record.items) {
    ByteReader in(item.bytes);
    switch (item.item) {
      case 10:
        p.source = fields::get_data_source(in);
        break;
      case 140: {
        const auto time = fields::get_time_of_day(in);
        if (!time) return {std::nullopt, Refusal::value_out_of_range};
        p.time_of_day_s = *time;
        break;
      }
      case 20: {
        const auto primary = in.get(1);
        p.detection = static_cast<DetectionType>(primary >> 5 & 0x7u);
        p.simulated = (primary & 0x10u) != 0;
        p.test_target = item.bytes.size() > 1 && (item.bytes[1] & 0x80u) != 0;
        break;
      }
      case 40:
        p.range_m = in.get(2) / 256.0 * kMetresPerNauticalMile;
        p.azimuth_deg = fields::get_angle16(in);
        break;
      case 70:
        p.mode3a = static_cast<std::uint16_t>(in.get(2) & 07777u);
        break;
      case 90:
        p.flight_level = static_cast<double>(sign_extend(in.get(2), 14)) * 0.25;
        break;
      case 220:
        p.address = in.get(3);
        break;
      case 240: {
        auto callsign = fields::get_identification(in);
        if (!callsign) return {std::nullopt, Refusal::value_out_of_range};
        if (!callsign->empty()) p.callsign = std::move(*callsign);  // eight spaces: none
        break;
      }
      case 161:
        p.track_number = static_cast<std::uint16_t>(in.get(2) & 0x0FFFu);
        break;
      default:  // an item RadarPlot does not carry: measured by the walker, skipped here
        break;
    }
  }
  return {p, std::nullopt};
}

}  // namespace skyfuse::asterix
