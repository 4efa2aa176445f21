// Fuzz target: parse_scenario on arbitrary bytes. The loader's contract is a Scenario or a
// ConfigError naming the problem; any other exception, a crash, undefined behaviour or a hang is
// a finding. An accepted scenario must also hold only what the loader promises to have checked.
// Inputs whose validation is long by design are skipped (see costs_too_much).

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>
#include <typeinfo>

#include "skyfuse/registry/part_info.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/scenario/traffic_config.hpp"

namespace {

using skyfuse::Scenario;

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "scenario_loader_fuzz: %s\n", what);
  std::abort();
}

// Validation walks the whole trajectory, for every speed, past every station and manoeuvre:
// about 1 us per step, speed and station here (ASan, UBSan), so `steps: 10000000` takes over a
// minute. That is the loader doing its job, not a hang; such inputs are skipped, and kept out of
// the corpus, so that a timeout in a long run points at a real one. Work is counted the way the
// loader will see it, from the same YAML.
bool costs_too_much(std::string_view text) {
  constexpr double kBudget = 1e5;  // about 0.1 s
  try {
    const YAML::Node root = YAML::Load(std::string(text));
    std::int64_t steps = 0;
    if (!root.IsMap() || !YAML::convert<std::int64_t>::decode(root["steps"], steps)) return false;
    // Missing or not a list: the loader reads one item (one speed from velocity_mps) or none.
    const auto items = [](const YAML::Node& node) {
      return node.IsDefined() && node.IsSequence() ? static_cast<double>(node.size()) : 1.0;
    };
    const YAML::Node target = root["target"];
    if (!target.IsDefined() || !target.IsMap()) return false;
    const double per_step =
        items(target["speeds_kmh"]) * (items(root["stations"]) + items(target["manoeuvres"]));
    return static_cast<double>(steps) * per_step > kBudget;
  } catch (const YAML::Exception&) {
    return false;  // the loader will refuse it quickly
  }
}

bool finite_positive(double value) {
  return std::isfinite(value) && value > 0.0;
}

// The numbers a run computes with: a non-finite or non-positive one here would have passed the
// loader and surfaced later as NaN in a track.
void check_path(const skyfuse::TargetConfig& target) {
  if (target.speeds_mps.empty()) finding("no speed");
  for (double speed : target.speeds_mps) {
    if (!finite_positive(speed)) finding("speed not finite and > 0");
  }
  if (!target.initial_position_m.allFinite()) finding("initial position not finite");
  if (!(std::abs(target.direction.norm() - 1.0) < 1e-9)) finding("direction not a unit vector");
  for (const auto& m : target.manoeuvres) {
    if (!std::isfinite(m.start_s) || !finite_positive(m.duration_s) ||
        !m.acceleration_mps2.allFinite() || !std::isfinite(m.turn_rate_rad_s)) {
      finding("manoeuvre not finite");
    }
  }
}

void check_detection(const skyfuse::DetectionConfig& d) {
  if (!(d.probability > 0.0 && d.probability <= 1.0)) finding("P_D not in (0, 1]");
  if (!(d.field_of_view.max_range_m > 0.0)) finding("max range not > 0");
  if (!std::isfinite(d.field_of_view.min_elevation_rad)) finding("min elevation not finite");
  if (!(d.clutter_per_scan >= 0.0 &&
        d.clutter_per_scan <= skyfuse::DetectionConfig::kMaxClutterPerScan)) {
    finding("clutter not in [0, bound]");
  }
  if (d.clutter_per_scan > 0.0 && !std::isfinite(d.field_of_view.max_range_m)) {
    finding("clutter without a finite range");
  }
}

// Many aircraft: every path, range and setting a run would compute with.
void check_traffic(const Scenario& s) {
  const skyfuse::TrafficConfig& traffic = *s.traffic;
  for (const auto& target : traffic.targets) {
    check_path(target.path);
    if (!(target.appears_s >= 0.0) || (target.leaves_s && !(*target.leaves_s > target.appears_s))) {
      finding("target schedule not ordered");
    }
  }
  if (const auto& g = traffic.generator) {
    if (g->aircraft < 1 || g->aircraft > skyfuse::TrafficConfig::kMaxAircraft) {
      finding("aircraft out of bounds");
    }
    for (const auto& range : {g->east_m, g->north_m, g->height_m, g->speed_mps, g->leg_s,
                              g->turn_deg, g->turn_rate_deg_s}) {
      if (!std::isfinite(range[0]) || !std::isfinite(range[1]) || range[0] > range[1]) {
        finding("generator range not finite and ordered");
      }
    }
    if (!(g->speed_mps[0] > 0.0 && g->leg_s[0] > 0.0 && g->turn_rate_deg_s[0] > 0.0)) {
      finding("generator speed, leg or turn rate not > 0");
    }
  }
  check_detection(traffic.detection);
  for (const auto& station : s.stations) {
    if (!station.detection) finding("a station's detection not resolved by the loader");
    if (station.detection) check_detection(*station.detection);
  }
  const auto& t = s.tracker;
  if (!(t.association.gate_probability > 0.0 && t.association.gate_probability < 1.0) ||
      !(t.initiation.gate_probability > 0.0 && t.initiation.gate_probability < 1.0)) {
    finding("gate probability not in (0, 1)");
  }
  if (t.management.confirm_hits < 1 || t.management.confirm_window < t.management.confirm_hits ||
      t.management.confirm_window > 32 || t.management.delete_misses < 1) {
    finding("confirmation or deletion out of bounds");
  }
  if (!finite_positive(t.management.max_position_std_m) ||
      !finite_positive(t.initiation.velocity_std_mps) || !finite_positive(traffic.gospa.cutoff_m) ||
      !(traffic.gospa.order >= 1.0) || !std::isfinite(traffic.gospa.order)) {
    finding("tracker or metric setting not finite and > 0");
  }
}

void check_accepted(const Scenario& s) {
  if (!finite_positive(s.time_step_s) || s.steps < 1) finding("bad time_step_s or steps");
  if (s.stations.empty()) finding("no station");
  if (s.has_many_targets()) {
    check_traffic(s);
  } else {
    check_path(s.target);
  }
  for (const auto& station : s.stations) {
    if (!station.position_m.allFinite() || !finite_positive(station.weight)) {
      finding("station position or weight not finite");
    }
    const auto sensor = skyfuse::find_sensor(station.sensor.kind);
    if (!sensor) finding("a sensor kind that is not registered");
    if (station.sensor.noise_std.size() != sensor->measurement_dim) {
      finding("noise_std not one value per measured component");
    }
    for (double sigma : station.sensor.noise_std) {
      if (!finite_positive(sigma)) finding("noise_std not finite and > 0");
    }
  }
  const auto model = skyfuse::find_motion_model(s.filter.motion_model.kind);
  if (!model) finding("a motion model that is not registered");
  if (s.filter.motion_model.process_noise_std.size() !=
      static_cast<Eigen::Index>(model->noise_fields.size())) {
    finding("process noise not one value per field of the model");
  }
  for (double q : s.filter.motion_model.process_noise_std) {
    if (!finite_positive(q)) finding("process noise not finite and > 0");
  }
  if (s.filter.initial_covariance_diag.size() != model->state_dim) {
    finding("initial covariance not one value per state component");
  }
  for (double p : s.filter.initial_covariance_diag) {
    if (!finite_positive(p)) finding("initial covariance not finite and > 0");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  if (costs_too_much(text)) return -1;
  try {
    check_accepted(skyfuse::parse_scenario(text, "fuzz.yaml"));
  } catch (const skyfuse::ConfigError&) {
    // The documented refusal.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scenario_loader_fuzz: %s escaped the loader: %s\n", typeid(e).name(),
                 e.what());
    std::abort();
  }
  return 0;
}
