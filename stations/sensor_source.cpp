#include "sensor_source.hpp"

#include <fmt/format.h>

#include <charconv>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "skyfuse/validation/physical_bounds.hpp"

namespace skyfuse::station {

SimulatedSensor::SimulatedSensor(const RunPlan& plan, const StationConfig& station)
    : truth_(plan.truth()),
      sensor_(station.position_m),
      noise_(station_noise_covariance<3>(plan.scenario, station, plan.mc_run)),
      seed_(plan.scenario.seed),
      mc_run_(plan.mc_run),
      station_id_(station.id) {}

Vector3 SimulatedSensor::measurement(std::uint64_t step) {
  if (step >= truth_.states.size()) {
    throw std::out_of_range(fmt::format("no simulated measurement for step {}", step));
  }
  return simulate_measurement(sensor_, truth_.states[step], noise_, seed_, mc_run_, station_id_,
                              step);
}

namespace {

constexpr const char* kReplayHeader = "step,station_id,range_m,azimuth_rad,elevation_rad";

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma - start));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

template <typename T>
bool parse(std::string_view text, T& value) {
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

}  // namespace

ReplayedSensor::ReplayedSensor(const std::filesystem::path& csv, int station_id) : path_(csv) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open replay file", csv.string()));
  std::string line;
  if (!std::getline(in, line) || line != kReplayHeader) {
    throw std::runtime_error(
        fmt::format("{}: line 1: expected the header '{}'", csv.string(), kReplayHeader));
  }
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const auto f = split(line);
    std::uint64_t step = 0;
    int id = 0;
    Vector3 z;
    const bool ok = f.size() == 5 && parse(f[0], step) && parse(f[1], id) && parse(f[2], z(0)) &&
                    parse(f[3], z(1)) && parse(f[4], z(2));
    if (!ok || !z.allFinite()) {
      throw std::runtime_error(fmt::format("{}: line {}: expected {} with finite numbers, got '{}'",
                                           csv.string(), number, kReplayHeader, line));
    }
    if (id != station_id) continue;
    if (transport::WireSensor::check_reported(z)) {
      throw std::runtime_error(fmt::format(
          "{}: line {}: station {} step {}: range must be in (0, {}] m, azimuth in [-pi, pi] and "
          "elevation in [-pi/2, pi/2] rad, got {}, {}, {}",
          csv.string(), number, id, step, kMaxRangeM, z(0), z(1), z(2)));
    }
    if (!rows_.emplace(step, z).second) {
      throw std::runtime_error(fmt::format("{}: line {}: second row for station {} at step {}",
                                           csv.string(), number, id, step));
    }
  }
}

Vector3 ReplayedSensor::measurement(std::uint64_t step) {
  const auto it = rows_.find(step);
  if (it == rows_.end()) {
    throw std::runtime_error(
        fmt::format("{}: no measurement for step {} of this station", path_.string(), step));
  }
  return it->second;
}

}  // namespace skyfuse::station
