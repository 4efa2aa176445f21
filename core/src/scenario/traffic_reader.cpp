#include "scenario/traffic_reader.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>

#include "skyfuse/picture/associator.hpp"
#include "skyfuse/picture/registration.hpp"

namespace skyfuse::detail {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

// [low, high] with low <= high, each checked by `check` (e.g. positive).
std::array<double, 2> read_range(const YamlField& field, bool positive) {
  const Eigen::VectorXd pair = field.numbers(2);
  if (pair(0) > pair(1)) {
    field.fail(fmt::format("expected [low, high] with low <= high, got '{}'", field.text()));
  }
  if (positive && !(pair(0) > 0.0)) {
    field.fail(fmt::format("must be > 0, got '{}'", field.text()));
  }
  return {pair(0), pair(1)};
}

TrafficGeneratorConfig read_generator(const YamlField& field) {
  field.allow_only({"aircraft", "east_m", "north_m", "height_m", "speed_mps", "leg_s", "turn_deg",
                    "turn_rate_deg_s", "appear_within_s"});
  TrafficGeneratorConfig g;
  const YamlField aircraft = field.required("aircraft");
  const std::int64_t n = aircraft.integer();
  if (n < 1 || n > TrafficConfig::kMaxAircraft) {
    aircraft.fail(fmt::format("must be an integer in [1, {}], got {}", TrafficConfig::kMaxAircraft,
                              aircraft.text()));
  }
  g.aircraft = static_cast<int>(n);
  if (const auto f = field.optional("east_m")) g.east_m = read_range(*f, false);
  if (const auto f = field.optional("north_m")) g.north_m = read_range(*f, false);
  if (const auto f = field.optional("height_m")) g.height_m = read_range(*f, false);
  if (const auto f = field.optional("speed_mps")) g.speed_mps = read_range(*f, true);
  if (const auto f = field.optional("leg_s")) g.leg_s = read_range(*f, true);
  if (const auto f = field.optional("turn_deg")) g.turn_deg = read_range(*f, true);
  if (const auto f = field.optional("turn_rate_deg_s")) g.turn_rate_deg_s = read_range(*f, true);
  if (const auto f = field.optional("appear_within_s")) {
    g.appear_within_s = f->non_negative_number();
  }
  return g;
}

RecordedTrafficConfig read_recorded(const YamlField& field) {
  field.allow_only({"file", "start_time_s", "max_staleness_s"});
  RecordedTrafficConfig r;
  r.file = field.required("file").string();
  if (const auto f = field.optional("start_time_s")) r.start_time_s = f->non_negative_number();
  if (const auto f = field.optional("max_staleness_s")) r.max_staleness_s = f->positive_number();
  return r;
}

ScheduledTarget read_scheduled_target(const YamlField& field) {
  static constexpr std::array<std::string_view, 2> kSchedule = {"appears_s", "leaves_s"};
  ScheduledTarget target;
  target.path = read_target(field, kSchedule);
  if (const auto f = field.optional("appears_s")) target.appears_s = f->non_negative_number();
  if (const auto f = field.optional("leaves_s")) {
    target.leaves_s = f->positive_number();
    if (*target.leaves_s <= target.appears_s) {
      f->fail(fmt::format("must be after appears_s ({}), got {}", target.appears_s, f->text()));
    }
  }
  return target;
}

// A probability in (0, 1].
double read_probability(const YamlField& field) {
  const double p = field.positive_number();
  if (p > 1.0) field.fail(fmt::format("must be in (0, 1], got {}", field.text()));
  return p;
}

}  // namespace

TrackerConfig read_tracker(const YamlField& field) {
  field.allow_only({"associator", "gate_probability", "max_detections_per_scan", "clutter_density",
                    "jpda_max_events", "confirm", "delete_after_misses", "max_position_std_m",
                    "initiation", "identity", "registration", "updater"});
  TrackerConfig t;
  if (const auto f = field.optional("associator")) {
    const std::string name = f->string();
    if (find_associator(name) == nullptr) {
      f->fail(fmt::format("unknown associator '{}'; known: {}", name, associator_names()));
    }
    t.association.associator = name;
  }
  if (const auto f = field.optional("clutter_density")) {
    t.association.clutter_density = f->positive_number();
  }
  if (const auto f = field.optional("jpda_max_events")) {
    const std::int64_t n = f->integer();
    if (n < 1 || n > 100'000'000) {
      f->fail(fmt::format("must be in [1, 100000000], got {}", f->text()));
    }
    t.association.jpda_max_events = static_cast<std::size_t>(n);
  }
  if (const auto f = field.optional("gate_probability")) {
    t.association.gate_probability = read_probability(*f);
    if (t.association.gate_probability >= 1.0) f->fail("must be < 1");
  }
  if (const auto f = field.optional("max_detections_per_scan")) {
    const std::int64_t n = f->integer();
    if (n < 1 || n > 65535) f->fail(fmt::format("must be in [1, 65535], got {}", f->text()));
    t.association.max_detections_per_scan = static_cast<std::size_t>(n);
  }
  if (const auto f = field.optional("confirm")) {
    const auto items = f->sequence();
    if (items.size() != 2)
      f->fail(fmt::format("expected [M, N] (M hits of N), got '{}'", f->text()));
    const std::int64_t m = items[0].integer();
    const std::int64_t n = items[1].integer();
    if (m < 1 || n < m || n > 32) {
      f->fail(fmt::format("expected 1 <= M <= N <= 32, got '{}'", f->text()));
    }
    t.management.confirm_hits = static_cast<int>(m);
    t.management.confirm_window = static_cast<int>(n);
  }
  if (const auto f = field.optional("delete_after_misses")) {
    const std::int64_t k = f->integer();
    if (k < 1 || k > 1000) f->fail(fmt::format("must be in [1, 1000], got {}", f->text()));
    t.management.delete_misses = static_cast<int>(k);
  }
  if (const auto f = field.optional("max_position_std_m")) {
    t.management.max_position_std_m = f->positive_number();
  }
  if (const auto registration = field.optional("registration")) {
    registration->allow_only({"kind", "prior_std"});
    const YamlField kind = registration->required("kind");
    const std::string name = kind.string();
    if (find_registration(name) == nullptr) {
      kind.fail(fmt::format("unknown registration '{}'; known: {}", name, registration_names()));
    }
    t.registration.kind = name;
    if (const auto prior = registration->optional("prior_std")) {
      prior->allow_only({"range_m", "azimuth_rad", "elevation_rad", "time_s"});
      if (const auto f = prior->optional("range_m"))
        t.registration.range_std_m = f->positive_number();
      if (const auto f = prior->optional("azimuth_rad")) {
        t.registration.azimuth_std_rad = f->positive_number();
      }
      if (const auto f = prior->optional("elevation_rad")) {
        t.registration.elevation_std_rad = f->positive_number();
      }
      if (const auto f = prior->optional("time_s"))
        t.registration.time_std_s = f->positive_number();
    }
  }
  if (const auto updater = field.optional("updater")) {
    updater->allow_only({"relinearisations"});
    if (const auto f = updater->optional("relinearisations")) {
      const std::int64_t n = f->integer();
      if (n < 0 || n > UpdaterConfig::kMaxRelinearisations) {
        f->fail(fmt::format("must be in [0, {}], got {}", UpdaterConfig::kMaxRelinearisations,
                            f->text()));
      }
      t.updater.relinearisations = static_cast<int>(n);
    }
  }
  if (const auto identity = field.optional("identity")) {
    identity->allow_only({"sanity_gate_probability", "merge_probability"});
    if (const auto f = identity->optional("sanity_gate_probability")) {
      t.identity.sanity_gate_probability = read_probability(*f);
      if (t.identity.sanity_gate_probability >= 1.0) f->fail("must be < 1");
    }
    if (const auto f = identity->optional("merge_probability")) {
      t.identity.merge_probability = f->non_negative_number();  // 0: no merge
      if (t.identity.merge_probability >= 1.0) {
        f->fail(fmt::format("must be in [0, 1) (0: no merge), got {}", f->text()));
      }
    }
  }
  if (const auto init = field.optional("initiation")) {
    init->allow_only({"min_stations", "gate_probability", "velocity_std_mps"});
    if (const auto f = init->optional("min_stations")) {
      const std::int64_t n = f->integer();
      if (n < 1 || n > 65535) f->fail(fmt::format("must be in [1, 65535], got {}", f->text()));
      t.initiation.min_stations = static_cast<int>(n);
    }
    if (const auto f = init->optional("gate_probability")) {
      t.initiation.gate_probability = read_probability(*f);
      if (t.initiation.gate_probability >= 1.0) f->fail("must be < 1");
    }
    if (const auto f = init->optional("velocity_std_mps")) {
      t.initiation.velocity_std_mps = f->positive_number();
    }
  }
  return t;
}

DetectionConfig read_detection(const YamlField& field, const DetectionConfig& defaults) {
  field.allow_only({"probability", "max_range_m", "min_elevation_deg", "azimuth_sector_deg",
                    "clutter_per_scan", "clutter_max_speed_mps", "reports_address",
                    "replays_broadcasts"});
  DetectionConfig d = defaults;
  if (const auto f = field.optional("probability")) d.probability = read_probability(*f);
  if (const auto f = field.optional("max_range_m"))
    d.field_of_view.max_range_m = f->positive_number();
  if (const auto f = field.optional("min_elevation_deg")) {
    const double deg = f->number();
    if (deg < -90.0 || deg >= 90.0) f->fail(fmt::format("must be in [-90, 90), got {}", f->text()));
    d.field_of_view.min_elevation_rad = deg * kDegToRad;
  }
  if (const auto f = field.optional("azimuth_sector_deg")) {
    const Eigen::VectorXd sector = f->numbers(2);
    if (!(sector(1) > 0.0 && sector(1) <= 180.0)) {
      f->fail(fmt::format("expected [centre, half width] with 0 < half width <= 180, got '{}'",
                          f->text()));
    }
    d.field_of_view.azimuth_sector = AzimuthSector{sector(0) * kDegToRad, sector(1) * kDegToRad};
  }
  if (const auto f = field.optional("reports_address")) d.reports_address = f->boolean();
  if (const auto f = field.optional("replays_broadcasts")) d.replays_broadcasts = f->boolean();
  if (const auto f = field.optional("clutter_max_speed_mps")) {
    d.clutter_max_speed_mps = f->non_negative_number();
  }
  if (const auto f = field.optional("clutter_per_scan")) {
    d.clutter_per_scan = f->non_negative_number();
    if (d.clutter_per_scan > DetectionConfig::kMaxClutterPerScan) {
      f->fail(fmt::format("{} false alarms per scan exceeds the bound of {}", f->text(),
                          DetectionConfig::kMaxClutterPerScan));
    }
  }
  return d;
}

TrafficConfig read_traffic(const YamlField& traffic, const std::optional<YamlField>& detection,
                           const std::optional<YamlField>& metrics) {
  traffic.allow_only({"targets", "generator", "recorded", "equipped_share"});
  TrafficConfig config;
  if (const auto targets = traffic.optional("targets")) {
    for (const YamlField& item : targets->sequence()) {
      config.targets.push_back(read_scheduled_target(item));
    }
  }
  if (const auto generator = traffic.optional("generator")) {
    config.generator = read_generator(*generator);
  }
  if (const auto recorded = traffic.optional("recorded"))
    config.recorded = read_recorded(*recorded);
  if (const auto f = traffic.optional("equipped_share")) {
    config.equipped_share = f->non_negative_number();
    if (config.equipped_share > 1.0) f->fail(fmt::format("must be in [0, 1], got {}", f->text()));
  }
  if (config.targets.empty() && !config.generator && !config.recorded) {
    traffic.fail("give at least one of 'targets', 'generator' or 'recorded'");
  }
  const std::size_t listed =
      config.targets.size() +
      (config.generator ? static_cast<std::size_t>(config.generator->aircraft) : 0U);
  if (listed > static_cast<std::size_t>(TrafficConfig::kMaxAircraft)) {
    traffic.fail(
        fmt::format("{} aircraft exceed the bound of {}", listed, TrafficConfig::kMaxAircraft));
  }
  if (detection) config.detection = read_detection(*detection, config.detection);
  if (metrics) {
    metrics->allow_only({"gospa_cutoff_m", "gospa_order"});
    if (const auto f = metrics->optional("gospa_cutoff_m"))
      config.gospa.cutoff_m = f->positive_number();
    if (const auto f = metrics->optional("gospa_order")) {
      config.gospa.order = f->number();
      if (config.gospa.order < 1.0) f->fail(fmt::format("must be >= 1, got {}", f->text()));
    }
  }
  return config;
}

}  // namespace skyfuse::detail
