#pragma once
// A recorded-traffic file written here in OpenSky's state-vector format (the project ships no
// third party's recording): 60 aircraft on straight, level legs through the area around
// `anchor`, a row every 10 s the way OpenSky writes them (time, and a position received a
// second earlier).

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "skyfuse/traffic/geodesy.hpp"

namespace skyfuse::test {

inline void write_opensky_states(const std::filesystem::path& path, const GeoAnchor& anchor,
                                 double start, int minutes) {
  std::ofstream out(path, std::ios::trunc);
  out << "time,icao24,lat,lon,velocity,heading,vertrate,callsign,onground,alert,spi,squawk,"
         "baroaltitude,geoaltitude,lastposupdate,lastcontact\n";
  for (int t = 0; t <= minutes * 60; t += 10) {
    for (int a = 0; a < 60; ++a) {
      const double heading_deg = 6.0 * a;  // clockwise from north
      const double speed = 120.0 + 2.0 * a;
      const double h = heading_deg * std::numbers::pi / 180.0;
      const Vector3 velocity(speed * std::sin(h), speed * std::cos(h), 0.0);
      const Vector3 start_at(-40000.0 * std::sin(h) + 300.0 * (a % 7),
                             -40000.0 * std::cos(h) - 200.0 * (a % 5), 1500.0 + 150.0 * a);
      const Vector3 p = start_at + (t - 1.0) * velocity;  // the position is a second old
      const Vector3 geo = from_local_enu(anchor, p);
      out << fmt::format(
          "{},{:06x},{:.9f},{:.9f},{},{},0,TEST{:02d}  ,false,false,false,1000,{},{},"
          "{},{}\n",
          start + t, 0x3c0000 + a, geo(0), geo(1), speed, heading_deg, a, geo(2), geo(2),
          start + t - 1.0, start + t);
    }
  }
}

}  // namespace skyfuse::test
