#pragma once
/// \file
/// What the scenario loader needs to know of each registered part, without its type: names,
/// dimensions and the fields a scenario gives it. Kept apart from registry.hpp so that the
/// loader and the command line need not compile the models.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace skyfuse {

struct MotionModelInfo {
  std::string_view kind;
  int state_dim = 0;
  /// Names of the process-noise standard deviations, in the order the model takes them.
  std::vector<std::string_view> noise_fields;
  /// Leading state entries that are the position (models/state_position.hpp).
  int position_dim = 3;
};

struct SensorInfo {
  std::string_view kind;
  int measurement_dim = 0;
  /// The sensor reads state entries [0, state_entries): a model must have at least that many.
  int state_entries = 0;
  /// Whether the sensor stands somewhere (a ground station) rather than riding on the target.
  bool needs_site = false;
  /// Names of the measured components, in order (noise_std gives one value for each).
  std::vector<std::string_view> components;
  /// Whether one detection fixes a position (picture/fixes_position.hpp): a run with many
  /// aircraft takes only such sensors.
  bool fixes_position = false;
  /// Receivers beside the one at the station's position (`sensor.receivers_m`); 0 for a
  /// sensor of one receiver.
  int other_receivers = 0;
  /// Whether it measures no height and needs the heights it assumes (`sensor.height_band_m`,
  /// models/range_azimuth.hpp).
  bool assumes_height = false;
  /// Leading state entries it reads as the position (models/state_position.hpp): a model
  /// must keep a position of at least that many.
  int position_dim = 3;
};

std::vector<MotionModelInfo> motion_model_infos();
std::vector<SensorInfo> sensor_infos();
std::optional<MotionModelInfo> find_motion_model(std::string_view kind);
std::optional<SensorInfo> find_sensor(std::string_view kind);
/// "a, b, c": the registered names, for error messages.
std::string motion_model_kinds();
std::string sensor_kinds();

}  // namespace skyfuse
