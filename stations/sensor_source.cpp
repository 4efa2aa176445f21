#include "sensor_source.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <charconv>
#include <fstream>
#include <stdexcept>
#include <string_view>

namespace skyfuse::station {
namespace {

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

void throw_no_simulated_step(std::uint64_t step) {
  throw std::out_of_range(fmt::format("no simulated measurement for step {}", step));
}

void throw_no_replayed_step(const std::filesystem::path& csv, std::uint64_t step) {
  throw std::runtime_error(
      fmt::format("{}: no measurement for step {} of this station", csv.string(), step));
}

std::map<std::uint64_t, std::vector<double>> read_replay_rows(
    const std::filesystem::path& csv, int station_id, const std::vector<std::string>& components,
    bool (*reportable)(const std::vector<double>& values)) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open replay file", csv.string()));
  const std::string header = fmt::format("step,station_id,{}", fmt::join(components, ","));
  std::string line;
  if (!std::getline(in, line) || line != header) {
    throw std::runtime_error(
        fmt::format("{}: line 1: expected the header '{}'", csv.string(), header));
  }
  std::map<std::uint64_t, std::vector<double>> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const auto f = split(line);
    std::uint64_t step = 0;
    int id = 0;
    std::vector<double> values(components.size());
    bool ok = f.size() == components.size() + 2 && parse(f[0], step) && parse(f[1], id);
    for (std::size_t i = 0; ok && i < values.size(); ++i) {
      ok = parse(f[i + 2], values[i]) && std::isfinite(values[i]);
    }
    if (!ok) {
      throw std::runtime_error(fmt::format("{}: line {}: expected {} with finite numbers, got '{}'",
                                           csv.string(), number, header, line));
    }
    if (id != station_id) continue;
    if (!reportable(values)) {
      throw std::runtime_error(fmt::format(
          "{}: line {}: station {} step {}: not a value the sensor can report ({}), "
          "got {}",
          csv.string(), number, id, step, fmt::join(components, ", "), fmt::join(values, ", ")));
    }
    if (!rows.emplace(step, std::move(values)).second) {
      throw std::runtime_error(fmt::format("{}: line {}: second row for station {} at step {}",
                                           csv.string(), number, id, step));
    }
  }
  return rows;
}

}  // namespace skyfuse::station
