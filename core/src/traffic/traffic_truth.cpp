#include "skyfuse/traffic/traffic_truth.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include "skyfuse/random/counter_rng.hpp"
#include "skyfuse/scenario/traffic_config.hpp"

namespace skyfuse {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

// The states of `path` flown at its first speed from step `first` until step `end` (exclusive).
TargetTruth fly(std::string label, const TargetConfig& path, double time_step_s, int first,
                int end) {
  TargetTruth truth{std::move(label), first, {}};
  if (end <= first) return truth;
  const TruthTrajectory flown =
      generate_truth(path, path.speeds_mps.front(), time_step_s, end - first - 1);
  truth.states = flown.states;
  return truth;
}

double uniform_in(const std::array<double, 2>& range, CounterRng& rng) {
  return range[0] + (range[1] - range[0]) * rng.uniform();
}

// Aircraft `index` of the generator: straight legs joined by turns either way, until the run
// ends.
TargetTruth generated_aircraft(const TrafficGeneratorConfig& g, std::uint64_t seed, int index,
                               double time_step_s, int steps) {
  CounterRng rng({seed, 0, 0, static_cast<std::uint64_t>(index), NoiseStream::kTraffic});
  TargetConfig path;
  // Drawn one by one, height first, as every figure's traffic was: a call's arguments are
  // evaluated in an order C++ leaves open (GCC the last first, clang the first first).
  const double height_m = uniform_in(g.height_m, rng);
  const double north_m = uniform_in(g.north_m, rng);
  const double east_m = uniform_in(g.east_m, rng);
  path.initial_position_m = Vector3(east_m, north_m, height_m);
  const double heading = 2.0 * std::numbers::pi * rng.uniform();
  path.direction = Vector3(std::cos(heading), std::sin(heading), 0.0);
  path.speeds_mps = {uniform_in(g.speed_mps, rng)};
  const double appears_s = g.appear_within_s * rng.uniform();
  const double duration_s = steps * time_step_s - appears_s;
  for (double t = uniform_in(g.leg_s, rng); t < duration_s;) {
    Manoeuvre turn;
    turn.kind = Manoeuvre::Kind::kTurn;
    const double rate = uniform_in(g.turn_rate_deg_s, rng) * kDegToRad;
    turn.turn_rate_rad_s = rng.uniform() < 0.5 ? rate : -rate;
    turn.start_s = t;
    turn.duration_s = uniform_in(g.turn_deg, rng) * kDegToRad / rate;
    path.manoeuvres.push_back(turn);
    t += turn.duration_s + uniform_in(g.leg_s, rng);
  }
  const int first = static_cast<int>(std::ceil(appears_s / time_step_s));
  return fly(fmt::format("G{}", index), path, time_step_s, first, steps + 1);
}

// A recorded aircraft's own ICAO 24-bit address (its label's first six hex digits); none for a
// simulated one.
Address recorded_address(const TargetTruth& target) {
  unsigned long icao24 = 0;
  const std::string hex = target.label.substr(0, target.label.find('#'));
  if (hex.size() == 6 &&
      std::from_chars(hex.data(), hex.data() + hex.size(), icao24, 16).ptr == hex.data() + 6) {
    return static_cast<Address>(icao24);
  }
  return kNoAddress;
}

// A simulated aircraft's callsign: "SF" and its address's six hex digits (SFF00011).
Identification simulated_identification(Address address) {
  return *identification_of(fmt::format("SF{:06X}", address));
}

// Gives each aircraft its address, with probability `share` (each drawn from its own stream
// of `seed`, so that one aircraft's draw never shifts another's), and a simulated one its
// callsign; an aircraft without an address reports no callsign either.
void equip(std::vector<TargetTruth>& targets, double share, std::uint64_t seed) {
  for (std::size_t t = 0; t < targets.size(); ++t) {
    if (share < 1.0) {
      CounterRng rng({seed, 0, 0, static_cast<std::uint64_t>(t), NoiseStream::kEquipage});
      if (rng.uniform() >= share) {
        targets[t].identification = kNoIdentification;
        continue;
      }
    }
    // A simulated aircraft's address is from the block 0xF00000.
    const Address recorded = recorded_address(targets[t]);
    targets[t].address = recorded != kNoAddress ? recorded : static_cast<Address>(0xF00000U + t);
    if (recorded == kNoAddress) {
      targets[t].identification = simulated_identification(targets[t].address);
    }
  }
}

}  // namespace

std::optional<std::filesystem::path> recorded_traffic_file(const Scenario& scenario,
                                                           const std::string& recorded_file) {
  if (!recorded_file.empty()) return std::filesystem::path(recorded_file);
  if (!scenario.traffic || !scenario.traffic->recorded) return std::nullopt;
  std::filesystem::path file = scenario.traffic->recorded->file;
  if (file.is_relative() && !scenario.source_path.empty()) {
    file = std::filesystem::path(scenario.source_path).parent_path() / file;
  }
  return file;
}

TrafficTruth build_traffic_truth(const Scenario& scenario, const std::string& recorded_file) {
  if (!scenario.traffic) throw std::logic_error("build_traffic_truth: a scenario with one target");
  const TrafficConfig& traffic = *scenario.traffic;
  const double dt = scenario.time_step_s;
  const int end = scenario.steps + 1;
  TrafficTruth truth;
  for (std::size_t i = 0; i < traffic.targets.size(); ++i) {
    const ScheduledTarget& target = traffic.targets[i];
    const int first = static_cast<int>(std::ceil(target.appears_s / dt));
    const int last = target.leaves_s
                         ? std::min(end, static_cast<int>(std::floor(*target.leaves_s / dt)) + 1)
                         : end;
    truth.targets.push_back(fly(fmt::format("T{}", i), target.path, dt, first, last));
  }
  if (traffic.generator) {
    for (int a = 0; a < traffic.generator->aircraft; ++a) {
      truth.targets.push_back(
          generated_aircraft(*traffic.generator, scenario.seed, a, dt, scenario.steps));
    }
  }
  if (const auto file = recorded_traffic_file(scenario, recorded_file)) {
    RecordedTrafficOptions options;
    options.time_step_s = dt;
    options.steps = scenario.steps;
    if (traffic.recorded) {
      if (traffic.recorded->start_time_s) options.start_time_s = *traffic.recorded->start_time_s;
      options.max_staleness_s = traffic.recorded->max_staleness_s;
    }
    truth.recorded = read_opensky_states(*file, scenario.anchor, options);
    for (const TargetTruth& flight : truth.recorded->targets) truth.targets.push_back(flight);
  }
  equip(truth.targets, traffic.equipped_share, scenario.seed);
  return truth;
}

}  // namespace skyfuse
