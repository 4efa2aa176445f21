#pragma once
/// \file
/// Reads and validates a scenario. Every field is checked; the first problem found is thrown
/// as a ConfigError whose message names the source, the field path and the offending value,
/// e.g. `paper000.yaml: stations[2].noise_std[0]: must be > 0, got -0.1`.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Parses YAML text; `source` names it in error messages (a file name, or "<embedded>").
Scenario parse_scenario(std::string_view yaml_text, const std::string& source);

/// The text of a scenario file; a missing or unreadable file is a ConfigError.
std::string read_scenario_text(const std::filesystem::path& path);

/// Reads and parses a file; a missing or unreadable file is a ConfigError too.
Scenario load_scenario_file(const std::filesystem::path& path);

/// The default scenario (scenarios/paper000.yaml), compiled into the library.
std::string_view default_scenario_yaml();
Scenario load_default_scenario();
/// The file at `path`, or the default scenario when `path` is empty (what `--scenario` means).
Scenario load_scenario_or_default(const std::string& path);

/// Refuses anything a run cannot use: unknown station ids, a station closer to the target
/// than `kMinStationSeparationM` at any step of any listed speed, and so on. parse_scenario
/// calls it; it is public so that scenarios built in code can be checked the same way.
void validate_scenario(const Scenario& scenario, const std::string& source);

/// A station nearer than this to the target makes range and angles degenerate.
inline constexpr double kMinStationSeparationM = 1.0;

}  // namespace skyfuse
