#include "forged_scan.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "fault_step.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse::rogue {
namespace {

wire::PictureScan plausible_scan(std::uint64_t run, std::uint32_t step, int station) {
  wire::PictureScan s;
  s.run_id(run);
  s.step(step);
  s.station_id(station);
  s.sensor(std::string(RangeAzimuthElevation<kKinematicsDim>::kKind));
  s.measurement_dim(3);
  s.values({1500.0, 0.5, 0.3});
  s.unassociated({0});
  return s;
}

}  // namespace

std::vector<ScanAttack> scan_attacks_at(std::uint64_t run, std::uint32_t k, int victim) {
  std::vector<ScanAttack> attacks;
  const auto add = [&](DropKind kind, std::uint64_t r, int station) {
    attacks.push_back({kind, plausible_scan(r, fault_step(kind, k), station)});
    return &attacks.back().sample;
  };
  // As for increments: the impersonation first (fault_step.hpp).
  add(DropKind::kDuplicate, run, victim);
  add(DropKind::kWrongRun, run ^ 0x5a5a5a5aULL, victim);
  add(DropKind::kStaleStep, run, victim);
  add(DropKind::kFutureStep, run, victim);
  add(DropKind::kUnknownStation, run, 999);
  add(DropKind::kNonFinite, run, victim)->values()[1] = std::numeric_limits<double>::quiet_NaN();
  add(DropKind::kOutOfRange, run, victim)->values()[0] = -5.0;
  return attacks;
}

}  // namespace skyfuse::rogue
