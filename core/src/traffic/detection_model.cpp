#include "skyfuse/traffic/detection_model.hpp"

#include <algorithm>
#include <cmath>

#include "skyfuse/core/angles.hpp"

namespace skyfuse {

bool FieldOfView::contains(const Vector3& site, const Vector3& position) const {
  const Vector3 d = position - site;
  const double range = d.norm();
  if (range > max_range_m) return false;
  if (range > 0.0 && std::asin(d.z() / range) < min_elevation_rad) return false;
  if (azimuth_sector) {
    const double azimuth = std::atan2(d.y(), d.x());
    if (std::abs(wrap_angle(azimuth - azimuth_sector->centre_rad)) >
        azimuth_sector->half_width_rad) {
      return false;
    }
  }
  return true;
}

Vector3 FieldOfView::draw_point(const Vector3& site, CounterRng& rng) const {
  const double range = max_range_m * rng.uniform();
  const AzimuthSector sector = azimuth_sector.value_or(AzimuthSector{});
  const double azimuth = sector.centre_rad + sector.half_width_rad * (2.0 * rng.uniform() - 1.0);
  const double top = std::numbers::pi / 2.0;
  const double elevation = min_elevation_rad + (top - min_elevation_rad) * rng.uniform();
  const double horizontal = range * std::cos(elevation);
  return site + Vector3(horizontal * std::cos(azimuth), horizontal * std::sin(azimuth),
                        range * std::sin(elevation));
}

std::uint32_t draw_poisson(double mean, CounterRng& rng) {
  // Knuth's product of uniforms, in slices of mean <= 30 so that exp(-slice) never underflows:
  // a sum of independent Poisson counts is Poisson with the summed mean.
  constexpr double kSlice = 30.0;
  std::uint32_t count = 0;
  for (double left = mean; left > 0.0; left -= kSlice) {
    const double limit = std::exp(-std::min(left, kSlice));
    double product = rng.uniform();
    while (product > limit) {
      ++count;
      product *= rng.uniform();
    }
  }
  return count;
}

}  // namespace skyfuse
