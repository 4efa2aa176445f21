#include "forged_scan.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse::rogue {
namespace {

constexpr std::uint32_t kFarAhead = 1000;  // steps

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
  const auto add = [&](DropKind kind, std::uint64_t r, std::uint32_t step, int station) {
    attacks.push_back({kind, plausible_scan(r, step, station)});
    return &attacks.back().sample;
  };
  // As for increments: the impersonation first, its step k + 1 in every receiver's window
  // whether it has closed step k yet or not.
  add(DropKind::kDuplicate, run, k + 1, victim);
  add(DropKind::kWrongRun, run ^ 0x5a5a5a5aULL, k, victim);
  add(DropKind::kStaleStep, run, k - 1, victim);
  // Far enough ahead that a rogue that wakes late, on a loaded machine, still names a step no
  // receiver has reached: at k + 5 a run of 158 rounds/s caught up with it in 30 ms, and the
  // scan counted as a duplicate.
  add(DropKind::kFutureStep, run, k + kFarAhead, victim);
  add(DropKind::kUnknownStation, run, k, 999);
  add(DropKind::kNonFinite, run, k, victim)->values()[1] = std::numeric_limits<double>::quiet_NaN();
  add(DropKind::kOutOfRange, run, k, victim)->values()[0] = -5.0;
  return attacks;
}

}  // namespace skyfuse::rogue
