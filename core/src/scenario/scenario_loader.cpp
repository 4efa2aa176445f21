#include "skyfuse/scenario/scenario_loader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include "scenario/traffic_reader.hpp"
#include "scenario/yaml_field.hpp"
#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/registry/compiled_parts.hpp"
#include "skyfuse/registry/filter_info.hpp"
#include "skyfuse/registry/part_info.hpp"
#include "skyfuse/scenario/associator_choice.hpp"
#include "skyfuse/scenario/truth.hpp"
#include "skyfuse/validation/physical_bounds.hpp"

namespace skyfuse {
namespace {

using detail::YamlField;

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kKmhToMps = 1.0 / 3.6;

Vector3 read_vector3(const YamlField& field) {
  return field.numbers(3);
}

// Direction of flight from heading (from +x towards +y) and climb angle, both in degrees.
Vector3 direction_from_angles(double heading_deg, double climb_deg) {
  const double heading = heading_deg * kDegToRad;
  const double climb = climb_deg * kDegToRad;
  return Vector3(std::cos(climb) * std::cos(heading), std::cos(climb) * std::sin(heading),
                 std::sin(climb));
}

Manoeuvre read_manoeuvre(const YamlField& field) {
  Manoeuvre m;
  const std::string kind = field.required("kind").string();
  m.start_s = field.required("start_s").non_negative_number();
  m.duration_s = field.required("duration_s").positive_number();
  if (kind == "turn") {
    field.allow_only({"kind", "start_s", "duration_s", "rate_deg_s"});
    m.kind = Manoeuvre::Kind::kTurn;
    m.turn_rate_rad_s = field.required("rate_deg_s").number() * kDegToRad;
  } else if (kind == "accelerate") {
    field.allow_only({"kind", "start_s", "duration_s", "acceleration_mps2"});
    m.kind = Manoeuvre::Kind::kAccelerate;
    m.acceleration_mps2 = read_vector3(field.required("acceleration_mps2"));
  } else {
    field.required("kind").fail(
        fmt::format("unknown manoeuvre kind '{}' (allowed: turn, accelerate)", kind));
  }
  return m;
}

}  // namespace

namespace detail {

TargetConfig read_target(const YamlField& field, std::span<const std::string_view> also_allowed) {
  std::vector<std::string_view> allowed = {"initial_position_m", "velocity_mps", "speeds_kmh",
                                           "heading_deg",        "climb_deg",    "manoeuvres"};
  allowed.insert(allowed.end(), also_allowed.begin(), also_allowed.end());
  field.allow_only(allowed);
  TargetConfig target;
  target.initial_position_m = read_vector3(field.required("initial_position_m"));

  const auto velocity = field.optional("velocity_mps");
  const auto speeds = field.optional("speeds_kmh");
  if (velocity && speeds) {
    speeds->fail("give either velocity_mps or speeds_kmh (with heading_deg), not both");
  }
  if (velocity) {
    if (field.optional("heading_deg") || field.optional("climb_deg")) {
      velocity->fail("heading_deg and climb_deg go with speeds_kmh, not with velocity_mps");
    }
    const Vector3 v = read_vector3(*velocity);
    if (v.norm() <= 0.0) velocity->fail(fmt::format("must be non-zero, got {}", velocity->text()));
    target.direction = v.normalized();
    target.speeds_mps = {v.norm()};
  } else if (speeds) {
    const auto heading = field.optional("heading_deg");
    const auto climb = field.optional("climb_deg");
    target.direction =
        direction_from_angles(heading ? heading->number() : 0.0, climb ? climb->number() : 0.0);
    const auto items = speeds->sequence();
    if (items.empty()) speeds->fail("must list at least one speed");
    for (const YamlField& item : items) {
      target.speeds_mps.push_back(item.positive_number() * kKmhToMps);
    }
  } else {
    field.fail("missing field 'speeds_kmh' (or 'velocity_mps')");
  }

  if (const auto manoeuvres = field.optional("manoeuvres")) {
    for (const YamlField& item : manoeuvres->sequence()) {
      target.manoeuvres.push_back(read_manoeuvre(item));
      const Manoeuvre& added = target.manoeuvres.back();
      for (std::size_t i = 0; i + 1 < target.manoeuvres.size(); ++i) {
        const Manoeuvre& other = target.manoeuvres[i];
        const bool overlap = added.start_s < other.start_s + other.duration_s &&
                             other.start_s < added.start_s + added.duration_s;
        if (overlap) item.fail(fmt::format("overlaps manoeuvres[{}]", i));
      }
    }
  }
  return target;
}

}  // namespace detail

namespace {

using detail::read_target;

// "[range_m, azimuth_rad, elevation_rad]": what a sensor's noise_std lists.
std::string component_list(const SensorInfo& sensor) {
  std::string out;
  for (std::string_view c : sensor.components) out += (out.empty() ? "" : ", ") + std::string(c);
  return "[" + out + "]";
}

// One positive standard deviation per component the sensor measures.
Eigen::VectorXd read_noise_std(const YamlField& noise, const SensorInfo& sensor) {
  const auto items = noise.sequence();
  if (items.size() != sensor.components.size()) {
    noise.fail(fmt::format("expected {}, got '{}'", component_list(sensor), noise.text()));
  }
  Eigen::VectorXd out(static_cast<Eigen::Index>(items.size()));
  for (std::size_t i = 0; i < items.size(); ++i) {
    out(static_cast<Eigen::Index>(i)) = items[i].positive_number();
  }
  return out;
}

// The sites of a sensor's receivers beside the station's own, as many as it has.
std::vector<Vector3> read_receivers(const YamlField& field, const SensorInfo& sensor) {
  const auto items = field.sequence();
  if (items.size() != static_cast<std::size_t>(sensor.other_receivers)) {
    field.fail(fmt::format("a {} sensor has {} receivers beside the station's position; got {}",
                           sensor.kind, sensor.other_receivers, items.size()));
  }
  std::vector<Vector3> sites;
  for (const YamlField& item : items) sites.push_back(read_vector3(item));
  return sites;
}

// The heights a sensor that measures none assumes: [low, high], low below high, both finite.
HeightBand read_height_band(const YamlField& field) {
  const auto band = field.numbers(2);
  if (!(band(0) < band(1)) || std::abs(band(0)) > kMaxRangeM || std::abs(band(1)) > kMaxRangeM) {
    field.fail(fmt::format("expected [low_m, high_m] with low below high, got '{}'", field.text()));
  }
  return HeightBand{band(0), band(1)};
}

SensorConfig read_sensor(const YamlField& field) {
  field.allow_only({"kind", "noise_std", "receivers_m", "height_band_m"});
  SensorConfig sensor;
  const YamlField kind = field.required("kind");
  sensor.kind = kind.string();
  const std::optional<SensorInfo> info = find_sensor(sensor.kind);
  if (!info) {
    kind.fail(
        fmt::format("unknown sensor kind '{}' (registered: {})", sensor.kind, sensor_kinds()));
  }
  sensor.noise_std = read_noise_std(field.required("noise_std"), *info);
  const auto receivers = field.optional("receivers_m");
  if (info->other_receivers > 0) {
    sensor.receivers_m = read_receivers(field.required("receivers_m"), *info);
  } else if (receivers) {
    receivers->fail(
        fmt::format("a {} sensor has one receiver, at the station; remove it", sensor.kind));
  }
  const auto band = field.optional("height_band_m");
  if (info->assumes_height) {
    if (!band) {
      field.fail(
          fmt::format("a {} sensor measures no height: give the heights it assumes, height_band_m: "
                      "[low_m, high_m]",
                      sensor.kind));
    }
    sensor.height_band_m = read_height_band(*band);
  } else if (band) {
    band->fail(fmt::format("a {} sensor assumes no heights; remove it", sensor.kind));
  }
  return sensor;
}

StationConfig read_station(const YamlField& field) {
  // `noise_std` beside the id is paper 000's shorthand for a range/azimuth/elevation sensor.
  field.allow_only({"id", "position_m", "sensor", "noise_std", "weight", "detection", "bias"});
  StationConfig station;
  const YamlField id = field.required("id");
  const std::int64_t raw_id = id.integer();
  // Id 0 is reserved for draws shared by all stations (the initial estimate).
  if (raw_id < 1 || raw_id > 100000) {
    id.fail(fmt::format("must be an integer in [1, 100000], got {}", id.text()));
  }
  station.id = static_cast<int>(raw_id);

  const auto sensor = field.optional("sensor");
  const auto shorthand_noise = field.optional("noise_std");
  if (sensor && shorthand_noise) {
    shorthand_noise->fail("give the noise inside 'sensor', not beside it");
  }
  if (sensor) {
    station.sensor = read_sensor(*sensor);
  } else if (shorthand_noise) {
    station.sensor.kind = "range_azimuth_elevation";
    station.sensor.noise_std = read_noise_std(*shorthand_noise, *find_sensor(station.sensor.kind));
  } else {
    field.fail("missing field 'sensor' (e.g. {kind: range_azimuth_elevation, noise_std: [...]})");
  }

  const SensorInfo info = *find_sensor(station.sensor.kind);  // read_sensor checked the kind
  const auto position = field.optional("position_m");
  if (info.needs_site && !position) {
    field.fail(fmt::format("missing field 'position_m' (a {} sensor stands somewhere)", info.kind));
  }
  if (!info.needs_site && position) {
    position->fail(
        fmt::format("a {} sensor rides on the target and has no site; remove it", info.kind));
  }
  if (position) station.position_m = read_vector3(*position);
  if (const auto weight = field.optional("weight")) station.weight = weight->positive_number();
  return station;
}

NoiseScaleConfig read_noise_scale(const YamlField& field) {
  field.allow_only({"scale", "scale_floor"});
  NoiseScaleConfig config;
  if (const auto scale = field.optional("scale")) {
    const std::string model = scale->string();
    if (model == "paper") {
      config.model = NoiseScaleConfig::Model::kPaper;
    } else if (model == "none") {
      config.model = NoiseScaleConfig::Model::kNone;
    } else {
      scale->fail(fmt::format("unknown scale model '{}' (allowed: paper, none)", model));
    }
  }
  if (const auto floor = field.optional("scale_floor")) {
    config.floor = floor->positive_number();
    if (config.floor > 1.0) floor->fail(fmt::format("must be <= 1, got {}", floor->text()));
  }
  return config;
}

// One standard deviation per field the model names, e.g. {position_m: 0.5, velocity_mps: 0.1}.
Eigen::VectorXd read_process_noise(const YamlField& field, const MotionModelInfo& model) {
  if (!field.is_map()) {
    field.fail(fmt::format("expected a mapping {{{}}}, got '{}'",
                           fmt::join(model.noise_fields, ": ..., "), field.text()));
  }
  field.allow_only(model.noise_fields);
  Eigen::VectorXd noise(static_cast<Eigen::Index>(model.noise_fields.size()));
  for (std::size_t i = 0; i < model.noise_fields.size(); ++i) {
    noise(static_cast<Eigen::Index>(i)) =
        field.required(std::string(model.noise_fields[i])).positive_number();
  }
  return noise;
}

MotionModelConfig read_motion_model(const YamlField& field) {
  field.allow_only({"kind", "process_noise_std"});
  MotionModelConfig model;
  const YamlField kind = field.required("kind");
  model.kind = kind.string();
  const std::optional<MotionModelInfo> info = find_motion_model(model.kind);
  if (!info) {
    kind.fail(fmt::format("unknown motion model '{}' (registered: {})", model.kind,
                          motion_model_kinds()));
  }
  model.process_noise_std = read_process_noise(field.required("process_noise_std"), *info);
  return model;
}

// n numbers, or one number for all n.
Eigen::VectorXd read_diagonal(const YamlField& field, int n) {
  if (field.is_scalar()) return Eigen::VectorXd::Constant(n, field.positive_number());
  const auto items = field.sequence();
  if (static_cast<int>(items.size()) != n) {
    field.fail(fmt::format("expected 1 or {} numbers, got '{}'", n, field.text()));
  }
  Eigen::VectorXd out(n);
  for (int i = 0; i < n; ++i) out(i) = items[static_cast<std::size_t>(i)].positive_number();
  return out;
}

// Noise standard deviations {name: value, ...} of a mode outside the registry (the IMM's).
template <std::size_t N>
std::array<double, N> read_mode_noise(const YamlField& field, std::string_view mode,
                                      const std::array<std::string_view, N>& names) {
  const MotionModelInfo info{mode, 0, std::vector<std::string_view>(names.begin(), names.end())};
  const Eigen::VectorXd noise = read_process_noise(field, info);
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = noise(static_cast<Eigen::Index>(i));
  return out;
}

ImmConfig read_imm(const YamlField& field) {
  field.allow_only({"modes", "constant_velocity", "coordinated_turn", "stay_probability",
                    "initial_turn_rate_variance"});
  ImmConfig imm;
  if (const auto modes = field.optional("modes")) {
    if (!modes->is_sequence()) modes->fail("expected a list of mode names");
    imm.modes.clear();
    for (const YamlField& mode : modes->sequence()) {
      std::string name = mode.string();
      if (std::ranges::find(imm.modes, name) != imm.modes.end()) {
        mode.fail(fmt::format("mode '{}' is named twice", name));
      }
      imm.modes.push_back(std::move(name));
    }
  }
  if (const auto cv = field.optional("constant_velocity")) {
    imm.constant_velocity =
        read_mode_noise<2>(*cv, "constant_velocity", {"position_m", "velocity_mps"});
  }
  if (const auto ct = field.optional("coordinated_turn")) {
    imm.coordinated_turn = read_mode_noise<3>(*ct, "coordinated_turn",
                                              {"position_m", "velocity_mps", "turn_rate_radps"});
  }
  if (const auto stay = field.optional("stay_probability")) {
    imm.stay_probability = stay->positive_number();
    if (imm.stay_probability > 1.0) stay->fail(fmt::format("must be <= 1, got {}", stay->text()));
  }
  if (const auto variance = field.optional("initial_turn_rate_variance")) {
    imm.initial_turn_rate_variance = variance->positive_number();
  }
  return imm;
}

FilterConfig read_filter(const YamlField& field) {
  // `process_noise_std` directly under the filter is paper 000's shorthand for the
  // constant-acceleration model.
  field.allow_only({"kind", "motion_model", "process_noise_std", "initial_covariance_diag",
                    "initial_state_error", "imm"});
  FilterConfig filter;
  std::optional<FilterInfo> info = find_filter(filter.kind);  // the default, "ekf"
  if (const auto kind = field.optional("kind")) {
    filter.kind = kind->string();
    info = find_filter(filter.kind);
    if (!info) {
      kind->fail(fmt::format("unknown filter '{}' (registered: {})", filter.kind, filter_kinds()));
    }
  }
  if (!filter_part_compiled(filter.kind)) {
    field.fail(fmt::format("filter '{}' is not in this build (it has {}): {}", filter.kind,
                           kCompiledFilterParts, kHowToBuildEveryPart));
  }
  const auto model = field.optional("motion_model");
  const auto shorthand_noise = field.optional("process_noise_std");
  if (model && shorthand_noise) {
    shorthand_noise->fail("give the process noise inside 'motion_model', not beside it");
  }
  if (model) {
    filter.motion_model = read_motion_model(*model);
  } else if (shorthand_noise) {
    filter.motion_model.kind = "constant_acceleration_3d";
    filter.motion_model.process_noise_std =
        read_process_noise(*shorthand_noise, *find_motion_model(filter.motion_model.kind));
  } else {
    field.fail(
        "missing field 'motion_model' (e.g. {kind: constant_acceleration_3d, "
        "process_noise_std: {...}})");
  }
  if (!info->motion_model.empty() && filter.motion_model.kind != info->motion_model) {
    (model ? model->required("kind") : field)
        .fail(fmt::format("filter '{}' runs on {}, not '{}'", filter.kind, info->motion_model,
                          filter.motion_model.kind));
  }
  // The modes of a filter that has them (the IMM's CA mode is the scenario's model).
  if (const auto imm = field.optional("imm")) {
    if (info->mode_names.empty()) {
      std::vector<std::string_view> with_modes;
      for (const FilterInfo& f : filter_infos()) {
        if (!f.mode_names.empty() && std::ranges::find(with_modes, f.kind) == with_modes.end()) {
          with_modes.push_back(f.kind);
        }
      }
      imm->fail(fmt::format("only a filter of kind '{}' has modes; this one is '{}'",
                            fmt::join(with_modes, "' or '"), filter.kind));
    }
    filter.imm = read_imm(*imm);
    if (!find_filter(filter)) {
      const auto modes = imm->optional("modes");
      (modes ? *modes : *imm)
          .fail(fmt::format("no filter '{}' is registered with modes [{}]; registered: {}",
                            filter.kind, fmt::join(filter.imm.modes, ", "),
                            filter_mode_sets(filter.kind)));
    }
  }
  const int dim = find_motion_model(filter.motion_model.kind)->state_dim;
  filter.initial_covariance_diag = read_diagonal(field.required("initial_covariance_diag"), dim);

  if (const auto error = field.optional("initial_state_error")) {
    if (error->is_scalar()) {
      if (error->string() != "sampled") {
        error->fail(fmt::format("expected 'sampled' or a list of {} numbers, got '{}'", dim,
                                error->text()));
      }
    } else {
      filter.initial_state_error = error->numbers(dim);
    }
  }
  return filter;
}

ExchangeConfig read_network(const YamlField& field) {
  field.allow_only({"exchange", "fanout"});
  ExchangeConfig exchange;
  if (const auto kind = field.optional("exchange")) {
    const auto parsed = parse_exchange_kind(kind->string());
    if (!parsed) kind->fail(fmt::format("expected flat, tree or auto, got '{}'", kind->text()));
    exchange.kind = *parsed;
  }
  if (const auto fanout = field.optional("fanout")) {
    const std::int64_t k = fanout->integer();
    if (k < 2 || k > ExchangeConfig::kMaxFanout) {
      fanout->fail(fmt::format("must be an integer in [2, {}], got {}", ExchangeConfig::kMaxFanout,
                               fanout->text()));
    }
    exchange.fanout = static_cast<int>(k);
  }
  return exchange;
}

GeoAnchor read_anchor(const YamlField& field) {
  field.allow_only({"latitude_deg", "longitude_deg", "altitude_m"});
  GeoAnchor anchor;
  const YamlField latitude = field.required("latitude_deg");
  anchor.latitude_deg = latitude.number();
  // Not at a pole: east and north are defined there only as limits.
  if (!(std::abs(anchor.latitude_deg) < 89.0)) {
    latitude.fail(fmt::format("must be within (-89, 89) degrees, got {}", latitude.text()));
  }
  const YamlField longitude = field.required("longitude_deg");
  anchor.longitude_deg = longitude.number();
  if (!(std::abs(anchor.longitude_deg) <= 180.0)) {
    longitude.fail(fmt::format("must be within [-180, 180] degrees, got {}", longitude.text()));
  }
  if (const auto altitude = field.optional("altitude_m")) anchor.altitude_m = altitude->number();
  return anchor;
}

AsterixSource read_asterix_source(const YamlField& field) {
  field.allow_only({"sac", "sic"});
  AsterixSource source;
  const auto code = [](const YamlField& f) {
    const std::int64_t value = f.integer();
    if (value < 0 || value > 255) {
      f.fail(fmt::format("must be a whole number from 0 to 255 (8 bits), got {}", f.text()));
    }
    return static_cast<int>(value);
  };
  if (const auto sac = field.optional("sac")) source.sac = code(*sac);
  if (const auto sic = field.optional("sic")) source.sic = code(*sic);
  return source;
}

// A station's `bias:` (traffic/sensor_bias.hpp): offsets of components its sensor measures,
// and a clock offset, each within a bound that a bias, not a misalignment or a unit slip, keeps.
SensorBias read_bias(const YamlField& field, const SensorInfo& sensor) {
  field.allow_only({"range_m", "azimuth_rad", "elevation_rad", "time_s"});
  SensorBias bias;
  const auto offset = [&](std::string_view name, double bound, std::string_view bound_text,
                          double& into) {
    const auto f = field.optional(std::string(name));
    if (!f) return;
    if (name != "time_s" && std::ranges::find(sensor.components, name) == sensor.components.end()) {
      f->fail(fmt::format("a {} sensor measures no {} (it measures {})", sensor.kind, name,
                          fmt::join(sensor.components, ", ")));
    }
    const double value = f->number();
    if (!(std::abs(value) <= bound)) {
      f->fail(fmt::format("must be within +-{}, got {}", bound_text, f->text()));
    }
    into = value;
  };
  offset("range_m", 10000.0, "10000 m", bias.range_m);
  constexpr std::string_view kAngleBound =
      "0.1 rad (5.7 degrees: beyond it a misaligned antenna, or degrees given as radians)";
  offset("azimuth_rad", 0.1, kAngleBound, bias.azimuth_rad);
  offset("elevation_rad", 0.1, kAngleBound, bias.elevation_rad);
  offset("time_s", 10.0, "10 s", bias.time_s);
  return bias;
}

// What a run with many aircraft takes of station i and the filter.
void check_many_targets(const Scenario& s, std::size_t i, const YamlField& item,
                        const YamlField& filter_field, const FilterInfo& filter,
                        const SensorInfo& sensor) {
  if (!filter.tracks_many) {
    std::vector<std::string_view> taken;
    for (const FilterInfo& f : filter_infos()) {
      if (f.tracks_many && std::ranges::find(taken, f.kind) == taken.end()) taken.push_back(f.kind);
    }
    filter_field.fail(
        fmt::format("filter '{}' keeps no picture of many aircraft yet; with 'traffic' use {}",
                    filter.kind, fmt::join(taken, " or ")));
  }
  if (!sensor.fixes_position) {
    std::vector<std::string_view> fixing;
    for (const SensorInfo& other : sensor_infos()) {
      if (other.fixes_position) fixing.push_back(other.kind);
    }
    item.required("sensor").fail(fmt::format(
        "a {} sensor's detection fixes no position, so no track can start from it; a scenario "
        "with 'traffic' takes sensors that fix one ({})",
        sensor.kind, fmt::join(fixing, ", ")));
  }
  const DetectionConfig& detection = *s.stations[i].detection;
  if (detection.clutter_per_scan > 0.0 && !std::isfinite(detection.field_of_view.max_range_m)) {
    item.fail("clutter needs a field of view with a finite detection.max_range_m");
  }
  if (detection.replays_broadcasts) {
    const YamlField where = item.optional("detection").value_or(item);
    constexpr std::string_view kBroadcastSensor = PositionVelocity<kKinematicsDim>::kKind;
    if (sensor.kind != kBroadcastSensor) {
      where.fail(
          fmt::format("replays_broadcasts: a recorded broadcast is a {} report; station's "
                      "sensor is {}",
                      kBroadcastSensor, sensor.kind));
    }
    if (!detection.reports_address) {
      where.fail("replays_broadcasts: a broadcast carries its address; set reports_address: true");
    }
    if (!s.traffic->recorded) {
      where.fail(
          "replays_broadcasts: only recorded aircraft broadcast; the scenario has no "
          "traffic.recorded");
    }
  }
}

Scenario read_scenario(const YamlField& root) {
  root.allow_only({"name", "description", "seed", "time_step_s", "steps", "target", "traffic",
                   "detection", "tracker", "metrics", "stations", "measurement_noise", "filter",
                   "network", "anchor", "asterix"});
  Scenario s;
  s.name = root.required("name").string();
  if (const auto description = root.optional("description")) s.description = description->string();

  const YamlField seed = root.required("seed");
  const std::int64_t raw_seed = seed.integer();
  if (raw_seed < 0) seed.fail(fmt::format("must be >= 0, got {}", seed.text()));
  s.seed = static_cast<std::uint64_t>(raw_seed);

  s.time_step_s = root.required("time_step_s").positive_number();
  const YamlField steps = root.required("steps");
  const std::int64_t raw_steps = steps.integer();
  if (raw_steps < 1 || raw_steps > 100'000'000) {
    steps.fail(fmt::format("must be an integer in [1, 100000000], got {}", steps.text()));
  }
  s.steps = static_cast<int>(raw_steps);

  const auto target = root.optional("target");
  const auto traffic = root.optional("traffic");
  if (target && traffic)
    traffic->fail("give either 'target' (one aircraft) or 'traffic', not both");
  if (!target && !traffic) root.fail("missing field 'target' (one aircraft) or 'traffic' (many)");
  if (target) {
    s.target = read_target(*target, {});
    for (const char* key : {"detection", "tracker", "metrics"}) {
      if (const auto extra = root.optional(key)) {
        extra->fail("only a scenario with 'traffic' (many aircraft) takes it");
      }
    }
  } else {
    s.traffic = std::make_shared<const TrafficConfig>(
        detail::read_traffic(*traffic, root.optional("detection"), root.optional("metrics")));
    if (const auto tracker = root.optional("tracker")) s.tracker = detail::read_tracker(*tracker);
  }

  const YamlField stations = root.required("stations");
  const auto station_items = stations.sequence();
  if (station_items.empty()) stations.fail("must list at least one station");
  std::set<int> ids;
  for (const YamlField& item : station_items) {
    s.stations.push_back(read_station(item));
    if (!ids.insert(s.stations.back().id).second) {
      item.required("id").fail(fmt::format("duplicate station id {}", s.stations.back().id));
    }
  }

  if (const auto noise = root.optional("measurement_noise")) {
    s.noise_scale = read_noise_scale(*noise);
  }
  const YamlField filter = root.required("filter");
  s.filter = read_filter(filter);
  // Only the EKF's increment is H, h and R taken at a point that can move
  // (fusion/relinearised_increment.hpp).
  if (s.tracker.updater.relinearisations > 0 && s.filter.kind != "ekf") {
    root.required("tracker")
        .required("updater")
        .required("relinearisations")
        .fail(fmt::format("relinearises the EKF's increments; filter '{}' takes its own",
                          s.filter.kind));
  }
  if (const auto network = root.optional("network")) s.exchange = read_network(*network);
  if (const auto anchor = root.optional("anchor")) s.anchor = read_anchor(*anchor);
  if (const auto asterix = root.optional("asterix")) s.asterix = read_asterix_source(*asterix);

  const MotionModelInfo model = *find_motion_model(s.filter.motion_model.kind);
  const FilterInfo filter_info = *find_filter(s.filter.kind);
  for (std::size_t i = 0; i < s.stations.size(); ++i) {
    if (!filter_info.sensor.empty() && s.stations[i].sensor.kind != filter_info.sensor) {
      station_items[i].fail(fmt::format("filter '{}' needs {} receivers; station {} has {}",
                                        filter_info.kind, filter_info.sensor, s.stations[i].id,
                                        s.stations[i].sensor.kind));
    }
    // E.g. the IMM's modes each take the stations' sensor at their own dimension: one kind.
    if (filter_info.one_sensor_kind && s.stations[i].sensor.kind != s.stations[0].sensor.kind) {
      station_items[i].fail(fmt::format(
          "filter '{}' needs every station to have the same sensor kind; station {} has {}, "
          "station {} has {}",
          filter_info.kind, s.stations[0].id, s.stations[0].sensor.kind, s.stations[i].id,
          s.stations[i].sensor.kind));
    }
    const SensorInfo sensor = *find_sensor(s.stations[i].sensor.kind);
    // Each station's detection, resolved here once: its own over the scenario's, or the
    // scenario's.
    if (const auto detection = station_items[i].optional("detection")) {
      if (!s.traffic) detection->fail("only a scenario with 'traffic' (many aircraft) takes it");
      s.stations[i].detection = detail::read_detection(*detection, s.traffic->detection);
    } else if (s.traffic) {
      s.stations[i].detection = s.traffic->detection;
    }
    if (const auto bias = station_items[i].optional("bias")) {
      if (!s.traffic) bias->fail("only a scenario with 'traffic' (many aircraft) takes it");
      s.stations[i].detection->bias = read_bias(*bias, sensor);
      if (s.stations[i].detection->replays_broadcasts) {
        bias->fail("a replayed broadcast is the aircraft's own report; it takes no bias");
      }
    }
    if (s.traffic) check_many_targets(s, i, station_items[i], filter, filter_info, sensor);
    if (sensor.position_dim > model.position_dim) {
      station_items[i].fail(
          fmt::format("a {} sensor reads a {}-D position; motion model {} keeps a {}-D one",
                      sensor.kind, sensor.position_dim, model.kind, model.position_dim));
    }
    if (sensor.state_entries > model.state_dim) {
      station_items[i].fail(
          fmt::format("a {} sensor reads {} state entries; motion model {} has only {}",
                      sensor.kind, sensor.state_entries, model.kind, model.state_dim));
    }
  }
  if (s.traffic) {
    try {
      check_associator(s);
    } catch (const std::invalid_argument& e) {
      root.optional("tracker").value_or(root).fail(e.what());
    }
  }
  return s;
}

}  // namespace

void validate_scenario(const Scenario& scenario, const std::string& source) {
  for (double speed : scenario.target.speeds_mps) {
    const TruthTrajectory truth =
        generate_truth(scenario.target, speed, scenario.time_step_s, scenario.steps);
    for (std::size_t i = 0; i < scenario.stations.size(); ++i) {
      const StationConfig& station = scenario.stations[i];
      const std::optional<SensorInfo> sensor = find_sensor(station.sensor.kind);
      if (!sensor) {
        throw ConfigError(fmt::format("{}: stations[{}].sensor.kind: unknown sensor kind '{}'",
                                      source, i, station.sensor.kind));
      }
      if (!sensor->needs_site) continue;  // it rides on the target
      for (std::size_t k = 0; k < truth.states.size(); ++k) {
        const double distance = (truth.position(k) - station.position_m).norm();
        if (distance < kMinStationSeparationM) {
          throw ConfigError(fmt::format(
              "{}: stations[{}].position_m: [{}, {}, {}] is {:.3g} m from the target at step {} "
              "(t = {:.3f} s, speed {:.4g} km/h); a station must stay at least {} m away",
              source, i, station.position_m.x(), station.position_m.y(), station.position_m.z(),
              distance, k, static_cast<double>(k) * scenario.time_step_s, speed * 3.6,
              kMinStationSeparationM));
        }
      }
    }
  }
}

Scenario parse_scenario(std::string_view yaml_text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml_text));
  } catch (const YAML::Exception& e) {
    throw ConfigError(fmt::format("{}: not valid YAML: {}", source, e.what()));
  }
  if (!root.IsMap())
    throw ConfigError(fmt::format("{}: expected a YAML mapping at the top", source));
  Scenario scenario = read_scenario(YamlField(root, "", source));
  validate_scenario(scenario, source);
  return scenario;
}

std::string read_scenario_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(fmt::format("{}: cannot open scenario file", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Scenario load_scenario_file(const std::filesystem::path& path) {
  Scenario scenario = parse_scenario(read_scenario_text(path), path.string());
  scenario.source_path = path.string();
  return scenario;
}

Scenario load_default_scenario() {
  return parse_scenario(default_scenario_yaml(), "<embedded paper000.yaml>");
}

Scenario load_scenario_or_default(const std::string& path) {
  return path.empty() ? load_default_scenario() : load_scenario_file(path);
}

}  // namespace skyfuse
