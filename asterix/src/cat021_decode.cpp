// CAT021 ed. 2.6: the items encode_cat021_record writes, read back from a walked record.
#include <cmath>

#include "identification.hpp"
#include "item_fields.hpp"
#include "skyfuse/asterix/byte_reader.hpp"
#include "skyfuse/asterix/cat021.hpp"
#include "skyfuse/asterix/units.hpp"

namespace skyfuse::asterix {
namespace {

// The extended items' parts, absent ones as zero (the walker measured the item).
std::uint8_t part(std::span<const std::uint8_t> item, std::size_t i) {
  return i < item.size() ? item[i] : 0;
}

AdsbQuality read_quality(std::span<const std::uint8_t> item) {
  AdsbQuality q;
  q.nucr_or_nacv = static_cast<std::uint8_t>(part(item, 0) >> 5 & 0x7u);
  q.nucp_or_nic = static_cast<std::uint8_t>(part(item, 0) >> 1 & 0xFu);
  q.nic_baro = static_cast<std::uint8_t>(part(item, 1) >> 7 & 0x1u);
  q.sil = static_cast<std::uint8_t>(part(item, 1) >> 5 & 0x3u);
  q.nacp = static_cast<std::uint8_t>(part(item, 1) >> 1 & 0xFu);
  q.sil_supplement = static_cast<std::uint8_t>(part(item, 2) >> 5 & 0x1u);
  q.sda = static_cast<std::uint8_t>(part(item, 2) >> 3 & 0x3u);
  q.gva = static_cast<std::uint8_t>(part(item, 2) >> 1 & 0x3u);
  return q;
}

bool valid_position(double lat, double lon) {
  return std::fabs(lat) <= 90.0 && lon >= -180.0 && lon < 180.0;
}

}  // namespace

Cat021Decoded decode_cat021_record(const WalkedRecord& record) {
  if (!has_items(record, {10, 40, 71, 73, 80, 90})) return {std::nullopt, Refusal::missing_item};
  if (find_item(record, 130) == nullptr && find_item(record, 131) == nullptr) {
    return {std::nullopt, Refusal::missing_item};
  }
  const bool both = find_item(record, 130) != nullptr && find_item(record, 131) != nullptr;
  AdsbReport r;
  r.position_items = both                                ? PositionItems::both
                     : find_item(record, 131) != nullptr ? PositionItems::high_resolution
                                                         : PositionItems::low_resolution;
  for (const auto& item : record.items) {
    ByteReader in(item.bytes);
    switch (item.item) {
      case 10:
        r.source = fields::get_data_source(in);
        break;
      case 40:
        r.address_type = static_cast<std::uint8_t>(part(item.bytes, 0) >> 5 & 0x7u);
        if (r.address_type > 3) return {std::nullopt, Refusal::value_out_of_range};  // reserved
        r.altitude_reporting = static_cast<std::uint8_t>(part(item.bytes, 0) >> 3 & 0x3u);
        r.ground = (part(item.bytes, 1) & 0x40u) != 0;
        r.simulated = (part(item.bytes, 1) & 0x20u) != 0;
        r.test_target = (part(item.bytes, 1) & 0x10u) != 0;
        break;
      case 71:
      case 73: {
        const auto time = fields::get_time_of_day(in);
        if (!time) return {std::nullopt, Refusal::value_out_of_range};
        (item.item == 71 ? r.time_of_applicability_s : r.time_of_reception_s) = *time;
        break;
      }
      case 130:
      case 131: {
        if (item.item == 130 && both) break;  // the high-resolution position wins
        const unsigned bits = item.item == 130 ? 24 : 32;
        const unsigned scale = item.item == 130 ? 23 : 30;
        r.latitude_deg = fields::get_wgs84_angle(in, bits, scale);
        r.longitude_deg = fields::get_wgs84_angle(in, bits, scale);
        if (!valid_position(r.latitude_deg, r.longitude_deg)) {
          return {std::nullopt, Refusal::value_out_of_range};
        }
        break;
      }
      case 80:
        r.address = in.get(3);
        break;
      case 140: {
        const auto raw = in.get(2);
        if (raw == 0x7FFFu) return {std::nullopt, Refusal::value_out_of_range};  // "greater than"
        const double feet = static_cast<double>(sign_extend(raw, 16)) * 6.25;
        if (feet < -1500.0) return {std::nullopt, Refusal::value_out_of_range};
        r.geometric_height_m = feet * kMetresPerFoot;
        break;
      }
      case 90:
        r.quality = read_quality(item.bytes);
        break;
      case 157: {
        const auto raw = in.get(2);
        // RE set: the rate is only the avionics' bound, no value to fuse.
        if ((raw & 0x8000u) == 0) {
          r.vertical_rate_mps =
              static_cast<double>(sign_extend(raw, 15)) * 6.25 * kMetresPerFoot / 60.0;
        }
        break;
      }
      case 160: {
        const auto first = in.get(2);
        if ((first & 0x8000u) != 0) {  // RE: the speed is only a lower bound
          return {std::nullopt, Refusal::value_out_of_range};
        }
        GroundVector v;
        v.ground_speed_mps = first * std::ldexp(1.0, -14) * kMetresPerNauticalMile;
        v.track_angle_deg = fields::get_angle16(in);
        r.ground_vector = v;
        break;
      }
      case 170: {
        auto callsign = fields::get_identification(in);
        if (!callsign) return {std::nullopt, Refusal::value_out_of_range};
        if (!callsign->empty()) r.callsign = std::move(*callsign);  // eight spaces: none
        break;
      }
      default:  // an item AdsbReport does not carry: measured by the walker, skipped here
        break;
    }
  }
  return {r, std::nullopt};
}

}  // namespace skyfuse::asterix
