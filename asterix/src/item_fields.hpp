#pragma once
// Fields several categories share, written and read the same way: times of day, WGS-84
// angles, Mode 3/A codes, 24-bit addresses. Internal to the library.

#include <cstdint>
#include <optional>
#include <string_view>

#include "skyfuse/asterix/byte_reader.hpp"
#include "skyfuse/asterix/byte_writer.hpp"
#include "skyfuse/asterix/data_source.hpp"

namespace skyfuse::asterix::fields {

/// I0xx/010: SAC then SIC, one octet each.
void put_data_source(ByteWriter& out, const DataSource& source);
DataSource get_data_source(ByteReader& in);

/// Times of day (I062/070, I048/140, I021/071, I021/073): 24 bits unsigned, LSB 1/128 s.
inline constexpr double kTimeLsb = 1.0 / 128.0;
/// [0, 86400) s; a time that rounds to 86400 s is midnight, written as 0.
void put_time_of_day(ByteWriter& out, std::string_view item, double seconds);
/// The time, or nullopt when it is not below 86400 s.
std::optional<double> get_time_of_day(ByteReader& in);

/// A latitude, [-90, 90] deg, as a `bits` two's complement count of 180/2^`scale` deg.
void put_latitude(ByteWriter& out, std::string_view item, double deg, unsigned bits,
                  unsigned scale);
/// A longitude, [-180, 180] deg: 180 and what rounds to it is written as -180 (the same
/// meridian; the field's range stops short of +180).
void put_longitude(ByteWriter& out, std::string_view item, double deg, unsigned bits,
                   unsigned scale);
/// The angle a `bits` two's complement count of 180/2^`scale` deg stands for.
double get_wgs84_angle(ByteReader& in, unsigned bits, unsigned scale);

/// An azimuth or track angle: any value, taken mod 360, as 16 bits of 360/2^16 deg.
void put_angle16(ByteWriter& out, double deg);
double get_angle16(ByteReader& in);

/// A Mode 3/A code in 2 octets: 12 bits whose four octal digits (3 bits each) are the code's,
/// under four flag bits (V, G, CH or L, spare) written as 0: validated, not garbled, unchanged.
void put_mode3a(ByteWriter& out, std::string_view item, std::uint16_t code);

/// A 24-bit address (ICAO aircraft address).
void put_address(ByteWriter& out, std::string_view item, std::uint32_t address);

/// A value of the standard's stated range [lo, hi] (the field may hold more): refused when
/// outside, then written as put_quantity does.
void put_bounded(ByteWriter& out, std::string_view item, double value, double lo, double hi,
                 double lsb, unsigned octets, Signedness signedness);

}  // namespace skyfuse::asterix::fields
