#include "item_fields.hpp"

#include <cmath>
#include <string>

#include "skyfuse/asterix/units.hpp"

namespace skyfuse::asterix::fields {
namespace {

std::string describe(double value) {
  return std::to_string(value);
}

}  // namespace

void put_data_source(ByteWriter& out, const DataSource& source) {
  out.put(source.sac, 1);
  out.put(source.sic, 1);
}

DataSource get_data_source(ByteReader& in) {
  DataSource source;
  source.sac = static_cast<std::uint8_t>(in.get(1));
  source.sic = static_cast<std::uint8_t>(in.get(1));
  return source;
}

void put_time_of_day(ByteWriter& out, std::string_view item, double seconds) {
  if (!(seconds >= 0.0 && seconds < kSecondsPerDay)) {
    out.fail(item, "time of day " + describe(seconds) + " s is not in [0, 86400)", 3);
    return;
  }
  auto count = std::llround(seconds / kTimeLsb);
  if (count >= std::llround(kSecondsPerDay / kTimeLsb)) count = 0;  // rounds to midnight
  out.put(static_cast<std::uint32_t>(count), 3);
}

std::optional<double> get_time_of_day(ByteReader& in) {
  const double seconds = in.get(3) * kTimeLsb;
  if (seconds >= kSecondsPerDay) return std::nullopt;
  return seconds;
}

void put_latitude(ByteWriter& out, std::string_view item, double deg, unsigned bits,
                  unsigned scale) {
  if (!(deg >= -90.0 && deg <= 90.0)) {
    out.fail(item, "latitude " + describe(deg) + " deg is not in [-90, 90]", bits / 8);
    return;
  }
  out.put_quantity(item, deg, 180.0 / std::ldexp(1.0, static_cast<int>(scale)), bits / 8,
                   Signedness::twos_complement);
}

void put_longitude(ByteWriter& out, std::string_view item, double deg, unsigned bits,
                   unsigned scale) {
  if (!(deg >= -180.0 && deg <= 180.0)) {
    out.fail(item, "longitude " + describe(deg) + " deg is not in [-180, 180]", bits / 8);
    return;
  }
  const double lsb = 180.0 / std::ldexp(1.0, static_cast<int>(scale));
  auto count = std::llround(deg / lsb);
  const auto half_turn = std::llround(180.0 / lsb);
  if (count >= half_turn) count -= 2 * half_turn;  // +180 is -180
  const auto checked = quantise(static_cast<double>(count), 1.0, bits, Signedness::twos_complement);
  if (!checked) {
    out.fail(item, "longitude " + describe(deg) + " deg does not fit the field", bits / 8);
    return;
  }
  out.put(field_bits(*checked, bits), bits / 8);
}

double get_wgs84_angle(ByteReader& in, unsigned bits, unsigned scale) {
  const auto count = sign_extend(in.get(bits / 8), bits);
  return static_cast<double>(count) * 180.0 / std::ldexp(1.0, static_cast<int>(scale));
}

void put_angle16(ByteWriter& out, double deg) {
  constexpr double kLsb = 360.0 / 65536.0;
  if (!std::isfinite(deg)) {
    out.fail("angle", "not finite", 2);
    return;
  }
  double turn = std::fmod(deg, 360.0);
  if (turn < 0.0) turn += 360.0;
  const auto count = std::llround(turn / kLsb) % 65536;  // 359.999...° rounds to 0°
  out.put(static_cast<std::uint32_t>(count), 2);
}

double get_angle16(ByteReader& in) {
  return in.get(2) * (360.0 / 65536.0);
}

void put_mode3a(ByteWriter& out, std::string_view item, std::uint16_t code) {
  if (code > 07777) {
    out.fail(item, "Mode 3/A code " + std::to_string(code) + " has more than 4 octal digits", 2);
    return;
  }
  out.put(code, 2);
}

void put_address(ByteWriter& out, std::string_view item, std::uint32_t address) {
  if (address > 0xFFFFFFu) {
    out.fail(item, "address " + std::to_string(address) + " is wider than 24 bits", 3);
    return;
  }
  out.put(address, 3);
}

void put_bounded(ByteWriter& out, std::string_view item, double value, double lo, double hi,
                 double lsb, unsigned octets, Signedness signedness) {
  if (!(value >= lo && value <= hi)) {
    out.fail(item,
             describe(value) + " is outside the item's range [" + describe(lo) + ", " +
                 describe(hi) + "]",
             octets);
    return;
  }
  out.put_quantity(item, value, lsb, octets, signedness);
}

}  // namespace skyfuse::asterix::fields
