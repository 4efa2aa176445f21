#pragma once
// ADS-B's accuracy categories (RTCA DO-260B, as carried by CAT021's I021/090): the navigation
// accuracy category for position (NACp), a bound on the 95 % horizontal position error (EPU),
// and for velocity (NACv), a bound on the 95 % horizontal velocity error. A receiver turns a
// category into a σ for its filter; a simulator turns its σ into the category an aircraft
// with that error would broadcast. For a circular Gaussian error, 95 % lies within
// kHorizontal95 σ.

#include <cstdint>
#include <optional>

namespace skyfuse::asterix {

/// √χ²₂(0.95): the 95 % radius of a circular 2-D Gaussian of σ 1 per axis.
inline constexpr double kHorizontal95 = 2.447746830680816;

/// The best (largest) NACp whose bound holds a 95 % error of `epu_m`; 0 (unknown) for none.
std::uint8_t nacp_of_epu(double epu_m);
/// NACp's bound on the 95 % horizontal error, metres; nullopt for 0 (unknown) and codes above 11.
std::optional<double> epu_of_nacp(std::uint8_t nacp);

/// The best NACv whose bound holds a 95 % horizontal velocity error of `error_mps`; 0 for none.
std::uint8_t nacv_of_error(double error_mps);
/// NACv's bound, m/s; nullopt for 0 (unknown) and codes above 4.
std::optional<double> error_of_nacv(std::uint8_t nacv);

}  // namespace skyfuse::asterix
