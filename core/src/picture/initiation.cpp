#include "skyfuse/picture/initiation.hpp"

#include <algorithm>
#include <stdexcept>

#include "skyfuse/metrics/chi_square.hpp"

namespace skyfuse {
namespace {

// A group's fused position, in information form: Y = sum P_i^-1, y = sum P_i^-1 p_i.
struct Group {
  Covariance<3> information = Covariance<3>::Zero();
  Vector3 information_vector = Vector3::Zero();
  Vector3 position = Vector3::Zero();
  Covariance<3> covariance = Covariance<3>::Zero();
  std::vector<int> stations;
  Address address = kNoAddress;
  const PositionFix* velocity_from = nullptr;  // its first fix that reports a velocity

  // Empty again, keeping the stations' storage for the next group.
  void clear() {
    information.setZero();
    information_vector.setZero();
    position.setZero();
    covariance.setZero();
    stations.clear();
    address = kNoAddress;
    velocity_from = nullptr;
  }

  // Whether `fix` may join: not of a station already in it, nor of another address.
  bool admits(const PositionFix& fix) const {
    if (has(fix.station_id)) return false;
    return fix.address == kNoAddress || address == kNoAddress || fix.address == address;
  }
  bool add(const PositionFix& fix) {
    Covariance<3> information_after = information + fix.information;
    symmetrize(information_after);
    SmallCholesky<3> factor;
    if (!factor.compute(information_after)) return false;
    information = information_after;
    information_vector += fix.information * fix.position;
    covariance = factor.inverse();
    position = factor.solve(information_vector);
    stations.push_back(fix.station_id);
    if (address == kNoAddress) address = fix.address;
    if (velocity_from == nullptr && fix.velocity) velocity_from = &fix;
    return true;
  }
  bool has(int station_id) const {
    return std::find(stations.begin(), stations.end(), station_id) != stations.end();
  }
};

bool agrees(const Group& group, const PositionFix& fix, double threshold) {
  // d^T S^-1 d >= |d|^2 / lambda_max(S) >= |d|^2 / trace(S) for S = P_group + P_fix: a fix
  // farther than that bound allows fails the test below, so it is refused without factoring S
  // (most fixes are far apart: false alarms, other aircraft). The margin keeps a pair within
  // rounding of the bound for the exact test, so the decisions are the exact test's.
  const Vector3 difference = fix.position - group.position;
  const double trace = group.covariance.trace() + fix.covariance.trace();
  if (difference.squaredNorm() > threshold * trace * (1.0 + 1e-9)) return false;
  Covariance<3> sum = group.covariance + fix.covariance;
  symmetrize(sum);
  SmallCholesky<3> factor;
  if (!factor.compute(sum)) return false;
  return difference.dot(factor.solve(difference)) <= threshold;
}

}  // namespace

double join_gate(const InitiationConfig& config) {
  return chi_square_quantile(config.gate_probability, 3.0);
}

std::vector<NewTrack> initiate_tracks(std::span<const PositionFix> fixes, std::uint64_t step,
                                      const InitiationConfig& config, double gate) {
  for (std::size_t i = 1; i < fixes.size(); ++i) {
    const auto before = std::pair{fixes[i - 1].station_id, fixes[i - 1].detection};
    if (!(before < std::pair{fixes[i].station_id, fixes[i].detection})) {
      throw std::invalid_argument("initiate_tracks: fixes out of (station, detection) order");
    }
  }
  std::vector<char> used(fixes.size(), 0);
  std::vector<NewTrack> started;
  std::vector<Address> started_addresses;  // an address starts one track
  const auto already_started = [&](Address address) {
    return address != kNoAddress && std::find(started_addresses.begin(), started_addresses.end(),
                                              address) != started_addresses.end();
  };
  Group group;
  std::vector<std::size_t> members;
  for (std::size_t first = 0; first < fixes.size(); ++first) {
    if (used[first] || already_started(fixes[first].address)) continue;
    group.clear();
    if (!group.add(fixes[first])) continue;
    members.assign(1, first);
    for (std::size_t other = first + 1; other < fixes.size(); ++other) {
      if (used[other] || !group.admits(fixes[other]) || already_started(fixes[other].address)) {
        continue;
      }
      if (agrees(group, fixes[other], gate) && group.add(fixes[other])) {
        members.push_back(other);
      }
    }
    // An addressed group is the aircraft's own report: one station is enough.
    if (group.address == kNoAddress &&
        static_cast<int>(group.stations.size()) < config.min_stations) {
      continue;
    }
    for (const std::size_t m : members) used[m] = 1;
    NewTrack track{make_track_id(step, fixes[first].station_id, fixes[first].detection),
                   group.position, group.covariance, group.stations, members};
    track.address = group.address;
    if (group.address != kNoAddress && group.velocity_from != nullptr) {
      track.velocity = group.velocity_from->velocity;
      track.velocity_covariance = group.velocity_from->velocity_covariance;
    }
    if (group.address != kNoAddress) started_addresses.push_back(group.address);
    started.push_back(std::move(track));
  }
  return started;
}

}  // namespace skyfuse
