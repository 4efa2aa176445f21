#include "report/picture_channels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "report/foxglove_json.hpp"
#include "skyfuse/picture/registration.hpp"
#include "skyfuse/registration/bias_trace.hpp"
#include "skyfuse/traffic/geodesy.hpp"

namespace skyfuse::harness {
namespace {

using namespace foxglove;  // NOLINT(google-build-using-namespace): this file's vocabulary

constexpr Rgba kConfirmedColor{0.20, 0.45, 0.90, 1.0};
constexpr Rgba kTentativeColor{0.95, 0.70, 0.10, 1.0};
constexpr Rgba kDetectionColor{0.35, 0.35, 0.40, 0.8};
constexpr Rgba kFalseAlarmColor{0.85, 0.20, 0.20, 0.8};
// Sizes in metres: a city's picture spans kilometres.
constexpr double kTrackSize = 40.0;
constexpr double kAircraftSize = 20.0;
constexpr double kDetectionSize = 15.0;
constexpr double kStationSize = 60.0;

std::string picture_schema() {
  return titled(
             object_of({{"timestamp", time_schema()},          {"step", typed("integer")},
                        {"aircraft", typed("integer")},        {"confirmed", typed("integer")},
                        {"tentative", typed("integer")},       {"gospa", typed("number")},
                        {"gospa_in_view", typed("number")},    {"localisation", typed("number")},
                        {"missed", typed("number")},           {"false", typed("number")},
                        {"missed_aircraft", typed("integer")}, {"false_tracks", typed("integer")},
                        {"tracked", typed("integer")},         {"completeness", typed("number")},
                        {"spuriousness", typed("number")},     {"spurious", typed("integer")},
                        {"detections", typed("integer")},      {"false_alarms", typed("integer")},
                        {"peers_agree", typed("boolean")},     {"digest", typed("string")}}),
             "skyfuse.Picture")
      .dump();
}

std::string registration_schema() {
  const json entry = object_of({{"entry", typed("string")},
                                {"estimate", typed("number")},
                                {"sigma", typed("number")},
                                {"truth", typed("number")},
                                {"within_2sigma", typed("boolean")}});
  const json station = object_of({{"station", typed("integer")}, {"entries", array_of(entry)}});
  return titled(object_of({{"timestamp", time_schema()},
                           {"step", typed("integer")},
                           {"stations", array_of(station)}}),
                "skyfuse.Registration")
      .dump();
}

std::string geojson_schema() {
  return titled(object_of({{"geojson", typed("string")}}), "foxglove.GeoJSON").dump();
}

// A GeoJSON point (longitude, latitude, height on WGS-84) of ENU position `enu`.
json geojson_point(const GeoAnchor& anchor, const Vector3& enu, json properties) {
  const Vector3 geodetic = from_local_enu(anchor, enu);
  return {{"type", "Feature"},
          {"geometry",
           {{"type", "Point"}, {"coordinates", {geodetic.y(), geodetic.x(), geodetic.z()}}}},
          {"properties", std::move(properties)}};
}

// The first station's bias estimates of `frame`, each entry beside its truth (the scenario's,
// which only the harness knows) and whether it lies within 2 sigma of it.
json registration_message(const PicturePlan& plan, const PictureFrame& frame, json timestamp) {
  json stations = json::array();
  for (const FrameBias& bias : frame.biases) {
    const auto config =
        std::find_if(plan.scenario.stations.begin(), plan.scenario.stations.end(),
                     [&](const StationConfig& s) { return s.id == bias.station_id; });
    const SensorBias truth = config != plan.scenario.stations.end() && config->detection
                                 ? config->detection->bias
                                 : SensorBias{};
    json entries = json::array();
    for (std::size_t e = 0; e < BiasTrace::kEntries.size(); ++e) {
      const double sigma = bias_entry(bias.sigma, e);
      if (!(sigma > 0.0)) continue;  // the sensor has no such entry
      const double estimate = bias_entry(bias.estimate, e);
      const double truth_e = bias_entry(truth, e);
      entries.push_back({{"entry", BiasTrace::kEntries[e]},
                         {"estimate", estimate},
                         {"sigma", sigma},
                         {"truth", truth_e},
                         {"within_2sigma", std::abs(estimate - truth_e) <= 2.0 * sigma}});
    }
    stations.push_back({{"station", bias.station_id}, {"entries", std::move(entries)}});
  }
  return {
      {"timestamp", std::move(timestamp)}, {"step", frame.step}, {"stations", std::move(stations)}};
}

}  // namespace

PictureChannels::PictureChannels(const PicturePlan& plan, std::uint64_t epoch_ns)
    : plan_(plan), epoch_ns_(epoch_ns) {
  specs_ = {{"/scene", "foxglove.SceneUpdate", scene_update_schema()},
            {"/stations", "foxglove.SceneUpdate", scene_update_schema()},
            {"/tracks/geojson", "foxglove.GeoJSON", geojson_schema()},
            {"/skyfuse/round", "skyfuse.Round", round_schema()},
            {"/skyfuse/picture", "skyfuse.Picture", picture_schema()},
            {"/skyfuse/summary", "skyfuse.RunSummary", run_summary_schema()}};
  if (estimates_biases(plan.scenario.tracker.registration)) {
    specs_.push_back({"/skyfuse/registration", "skyfuse.Registration", registration_schema()});
  }
}

std::string PictureChannels::track_name(const FrameTrack& track) {
  // A track past the numbers (more than 65 535 at once) keeps its long id.
  return fmt::format("T{}", track.number != 0 ? track.number : track.id);
}

std::uint64_t PictureChannels::log_time_ns(int step) const {
  const double dt_ns = plan_.scenario.time_step_s * 1e9;
  return epoch_ns_ + static_cast<std::uint64_t>(std::llround(step * dt_ns));
}

std::vector<ChannelMessage> PictureChannels::frame_messages(const PictureFrame& frame, bool scene) {
  const std::uint64_t ns = log_time_ns(frame.step);
  std::vector<ChannelMessage> out;
  if (scene) {
    scene_messages(frame, ns, out);
  } else {
    follow(frame);
  }
  figure_messages(frame, ns, out);
  return out;
}

void PictureChannels::follow(const PictureFrame& frame) {
  // The trails take a point every kTrailEvery steps; a track gone takes its trail with it.
  const bool trail_step = frame.step % kTrailEvery == 0;
  std::map<std::uint64_t, std::vector<Vector3>> trails;
  for (const FrameTrack& t : frame.tracks) {
    if (!t.confirmed) continue;
    auto& points = trails[t.id];
    if (const auto old = trails_.find(t.id); old != trails_.end()) points = std::move(old->second);
    if (trail_step) {
      points.push_back(t.position);
      if (points.size() > kTrailPoints) points.erase(points.begin());
    }
  }
  trails_ = std::move(trails);
  trails_unsent_ = trails_unsent_ || trail_step;
  // Tracks the picture dropped and aircraft that left leave the next scene.
  std::set<std::string> shown;
  for (const FrameTrack& t : frame.tracks) shown.insert(fmt::format("track/{}", t.id));
  for (const TruthPoint& a : frame.aircraft) shown.insert(fmt::format("aircraft/{}", a.target));
  for (const std::string& id : shown_) {
    if (!shown.contains(id)) gone_.insert(id);
  }
  for (const std::string& id : shown) gone_.erase(id);
  shown_ = std::move(shown);
}

void PictureChannels::scene_messages(const PictureFrame& frame, std::uint64_t ns,
                                     std::vector<ChannelMessage>& out) {
  const auto emit = [&](Channel channel, const json& message) {
    out.push_back({channel, ns, message.dump()});
  };

  follow(frame);
  const bool with_trails = trails_unsent_;
  trails_unsent_ = false;
  json entities = json::array();
  for (const FrameTrack& t : frame.tracks) {
    const Rgba c = t.confirmed ? kConfirmedColor : kTentativeColor;
    json e = entity(ns, fmt::format("track/{}", t.id));
    e["metadata"].push_back({{"key", "track_id"}, {"value", std::to_string(t.id)}});
    const std::string name = track_name(t);
    e["metadata"].push_back({{"key", "track_number"}, {"value", name.substr(1)}});
    e["spheres"].push_back(shape(t.position, Vector3::Constant(kTrackSize), c));
    e["spheres"].push_back(ellipsoid(t.position, t.position_covariance, c));
    e["texts"].push_back(label(t.position + Vector3(0.0, 0.0, kTrackSize),
                               fmt::format("{}{}", name, t.confirmed ? "" : "?"), c));
    const auto trail = trails_.find(t.id);
    if (with_trails && trail != trails_.end() && trail->second.size() >= 2) {
      e["lines"].push_back(line_strip(trail->second, c));
    }
    entities.push_back(std::move(e));
  }
  for (const TruthPoint& a : frame.aircraft) {
    json e = entity(ns, fmt::format("aircraft/{}", a.target));
    e["spheres"].push_back(shape(a.position, Vector3::Constant(kAircraftSize), kTruthColor));
    entities.push_back(std::move(e));
  }
  for (const ScanPositions& scan : frame.scans) {
    json e = entity(ns, fmt::format("scan/{}", scan.station_id));
    for (std::size_t d = 0; d < scan.positions.size(); ++d) {
      e["cubes"].push_back(shape(scan.positions[d], Vector3::Constant(kDetectionSize),
                                 scan.target[d] < 0 ? kFalseAlarmColor : kDetectionColor));
    }
    entities.push_back(std::move(e));
  }
  json deletions = json::array();
  for (const std::string& id : gone_) {
    deletions.push_back({{"timestamp", stamp(ns)}, {"type", 0}, {"id", id}});
  }
  gone_.clear();
  emit(kScene, {{"deletions", std::move(deletions)}, {"entities", std::move(entities)}});

  if (!stations_sent_) {
    stations_sent_ = true;
    json sites = json::array();
    for (const StationConfig& s : plan_.participants()) {
      json e = entity(ns, fmt::format("site/{}", s.id));
      e["cubes"].push_back(shape(s.position_m, Vector3::Constant(kStationSize), kStationColor));
      e["texts"].push_back(label(s.position_m + Vector3(0.0, 0.0, kStationSize),
                                 fmt::format("{} ({})", s.id, s.sensor.kind), kStationColor));
      sites.push_back(std::move(e));
    }
    emit(kStations, {{"deletions", json::array()}, {"entities", std::move(sites)}});
  }

  json features = json::array();
  for (const FrameTrack& t : frame.tracks) {
    if (t.confirmed) {
      features.push_back(
          geojson_point(plan_.scenario.anchor, t.position, {{"name", track_name(t)}}));
    }
  }
  emit(
      kTracksGeoJson,
      {{"geojson", json{{"type", "FeatureCollection"}, {"features", std::move(features)}}.dump()}});
}

void PictureChannels::figure_messages(const PictureFrame& frame, std::uint64_t ns,
                                      std::vector<ChannelMessage>& out) const {
  const auto emit = [&](Channel channel, const json& message) {
    out.push_back({channel, ns, message.dump()});
  };
  std::size_t detections = 0;
  std::size_t false_alarms = 0;
  for (const ScanPositions& scan : frame.scans) {
    detections += scan.positions.size();
    false_alarms +=
        static_cast<std::size_t>(std::count(scan.target.begin(), scan.target.end(), -1));
  }
  const std::size_t confirmed = static_cast<std::size_t>(std::count_if(
      frame.tracks.begin(), frame.tracks.end(), [](const FrameTrack& t) { return t.confirmed; }));
  // The page's strip and slider read the rounds: a node is "some" when it fused fewer scans
  // than there are stations (which ones, a picture does not say).
  json nodes = json::array();
  bool all_in = true;
  for (const FrameNode& n : frame.nodes) {
    all_in = all_in && n.delivered && n.scans_fused == static_cast<std::uint32_t>(plan_.stations);
    nodes.push_back({{"node", n.node},
                     {"delivered", n.delivered},
                     {"contributors", json::array()},
                     {"missing", json::array()},
                     {"scans_fused", n.scans_fused}});
  }
  emit(kRounds, {{"timestamp", stamp(ns)},
                 {"step", frame.step},
                 {"time_s", frame.step * plan_.scenario.time_step_s},
                 {"latency_ms", frame.latency_ms},
                 {"all_inputs_in_time", all_in},
                 {"measurements", detections},
                 {"stations", plan_.stations},
                 {"nodes", std::move(nodes)},
                 {"refused", json::array()}});
  emit(kPicture,
       {{"timestamp", stamp(ns)},
        {"step", frame.step},
        {"aircraft", frame.score.aircraft},
        {"confirmed", confirmed},
        {"tentative", frame.tracks.size() - confirmed},
        {"gospa", frame.score.gospa.distance},
        // What the network can see: the aircraft in some station's view.
        {"gospa_in_view", frame.score.gospa_in_view.distance},
        {"localisation", frame.score.gospa.localisation},
        {"missed", frame.score.gospa.missed},
        {"false", frame.score.gospa.false_tracks},
        {"missed_aircraft", frame.score.gospa.missed_targets},
        {"false_tracks", frame.score.gospa.false_estimates},
        {"tracked", frame.score.tracked},
        // SIAP's two figures of one round: aircraft with a track, tracks without one.
        {"completeness", frame.score.aircraft == 0 ? 1.0
                                                   : static_cast<double>(frame.score.tracked) /
                                                         static_cast<double>(frame.score.aircraft)},
        {"spuriousness", frame.score.tracks == 0 ? 0.0
                                                 : static_cast<double>(frame.score.spurious) /
                                                       static_cast<double>(frame.score.tracks)},
        {"spurious", frame.score.spurious},
        {"detections", detections},
        {"false_alarms", false_alarms},
        {"peers_agree", frame.peers_agree},
        {"digest", fmt::format("{:016x}", frame.digest)}});
  if (estimates_biases(plan_.scenario.tracker.registration)) {
    emit(kRegistration, registration_message(plan_, frame, stamp(ns)));
  }
}

ChannelMessage PictureChannels::summary_message(std::string summary_json, int steps) const {
  return {kSummary, log_time_ns(steps), std::move(summary_json)};
}

}  // namespace skyfuse::harness
