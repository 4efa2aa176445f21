// CAT062 ed. 1.19: the items encode_cat062_record writes, read back from a walked record.
#include <cmath>

#include "identification.hpp"
#include "item_fields.hpp"
#include "skyfuse/asterix/byte_reader.hpp"
#include "skyfuse/asterix/cat062.hpp"
#include "skyfuse/asterix/units.hpp"

namespace skyfuse::asterix {
namespace {

bool has_bit(std::uint8_t octet, unsigned position) {
  return (octet >> (position - 1) & 1u) != 0;
}

TrackStatus read_track_status(std::span<const std::uint8_t> octets) {
  // The walker measured the extended item, so it has 1..6 octets; absent ones are defaults.
  const auto octet = [&octets](std::size_t i) -> std::uint8_t {
    return i < octets.size() ? octets[i] : 0;
  };
  TrackStatus s;
  s.mono_sensor = has_bit(octet(0), 8);
  s.altitude_source = static_cast<std::uint8_t>(octet(0) >> 2 & 0x7u);
  s.tentative = has_bit(octet(0), 2);
  s.simulated = has_bit(octet(1), 8);
  s.last_message = has_bit(octet(1), 7);
  s.first_message = has_bit(octet(1), 6);
  s.coasting = has_bit(octet(3), 8);
  s.psr_aged = has_bit(octet(3), 7);
  s.ssr_aged = has_bit(octet(3), 6);
  s.mode_s_aged = has_bit(octet(3), 5);
  s.adsb_aged = has_bit(octet(3), 4);
  return s;
}

TrackAccuracy read_accuracy(std::span<const std::uint8_t> item) {
  const auto subfields = uap_cat062()[frn_of(uap_cat062(), 500) - 1].format.subfields;
  TrackAccuracy a;
  for (const auto& sub : split_compound(item, subfields)) {
    ByteReader in(sub.bytes);
    switch (sub.index) {
      case 1:  // APC
        a.sigma_x_m = in.get(2) * 0.5;
        a.sigma_y_m = in.get(2) * 0.5;
        break;
      case 2: {  // COV: sign(cov)·sqrt(|cov|)
        const double root = static_cast<double>(sign_extend(in.get(2), 16)) * 0.5;
        a.covariance_xy_m2 = std::copysign(root * root, root);
        break;
      }
      case 4:  // AGA
        a.sigma_altitude_m = in.get(1) * 6.25 * kMetresPerFoot;
        break;
      case 6:  // ATV
        a.sigma_vx_mps = in.get(1) * 0.25;
        a.sigma_vy_mps = in.get(1) * 0.25;
        break;
      default:  // APW, ABA, AA, ARC: not carried by SystemTrack
        break;
    }
  }
  return a;
}

std::optional<std::uint32_t> read_address(std::span<const std::uint8_t> item) {
  const auto subfields = uap_cat062()[frn_of(uap_cat062(), 380) - 1].format.subfields;
  for (const auto& sub : split_compound(item, subfields)) {
    if (sub.index == 1) return ByteReader(sub.bytes).get(3);
  }
  return std::nullopt;
}

}  // namespace

Cat062Decoded decode_cat062_record(const WalkedRecord& record) {
  if (!has_items(record, {10, 40, 70, 80, 100, 105, 185}))
    return {std::nullopt, Refusal::missing_item};
  SystemTrack t;
  for (const auto& item : record.items) {
    ByteReader in(item.bytes);
    switch (item.item) {
      case 10:
        t.source = fields::get_data_source(in);
        break;
      case 15:
        t.service_id = static_cast<std::uint8_t>(in.get(1));
        break;
      case 70: {
        const auto time = fields::get_time_of_day(in);
        if (!time) return {std::nullopt, Refusal::value_out_of_range};
        t.time_of_track_s = *time;
        break;
      }
      case 105:
        t.latitude_deg = fields::get_wgs84_angle(in, 32, 25);
        t.longitude_deg = fields::get_wgs84_angle(in, 32, 25);
        if (std::fabs(t.latitude_deg) > 90.0 || t.longitude_deg >= 180.0 ||
            t.longitude_deg < -180.0) {
          return {std::nullopt, Refusal::value_out_of_range};
        }
        break;
      case 100:
        t.x_m = static_cast<double>(sign_extend(in.get(3), 24)) * 0.5;
        t.y_m = static_cast<double>(sign_extend(in.get(3), 24)) * 0.5;
        break;
      case 185:
        t.vx_mps = static_cast<double>(sign_extend(in.get(2), 16)) * 0.25;
        t.vy_mps = static_cast<double>(sign_extend(in.get(2), 16)) * 0.25;
        break;
      case 60:
        t.mode3a = static_cast<std::uint16_t>(in.get(2) & 07777u);
        break;
      case 245: {
        const auto sti = in.get(1) >> 6;
        auto callsign = fields::get_identification(in);
        if (!callsign) return {std::nullopt, Refusal::value_out_of_range};
        // STI 3 is "invalid"; eight spaces are no identification.
        if (sti != 3 && !callsign->empty()) t.callsign = std::move(*callsign);
        break;
      }
      case 380:
        t.address = read_address(item.bytes);
        break;
      case 40:
        t.track_number = static_cast<std::uint16_t>(in.get(2));
        break;
      case 80:
        t.status = read_track_status(item.bytes);
        break;
      case 130: {
        const double feet = static_cast<double>(sign_extend(in.get(2), 16)) * 6.25;
        if (feet < -1500.0 || feet > 150000.0) return {std::nullopt, Refusal::value_out_of_range};
        t.geometric_altitude_m = feet * kMetresPerFoot;
        break;
      }
      case 500:
        t.accuracy = read_accuracy(item.bytes);
        break;
      default:  // an item SystemTrack does not carry: measured by the walker, skipped here
        break;
    }
  }
  return {t, std::nullopt};
}

}  // namespace skyfuse::asterix
