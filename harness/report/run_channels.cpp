#include "report/run_channels.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

namespace skyfuse::harness {
namespace {

using nlohmann::json;

constexpr std::uint64_t kNsPerS = 1'000'000'000;
constexpr const char* kWorldFrame = "world";
// A 95 % region of a 3-D Gaussian: sqrt of the chi-square(3) 0.95 quantile (7.8147).
constexpr double kEllipsoidSigmas = 2.7955;

// ---- JSON schemas, for the fields skyfuse fills ------------------------------------------

json typed(const char* type) {
  return {{"type", type}};
}

json object_of(json properties) {
  json required = json::array();
  for (const auto& [key, value] : properties.items()) required.push_back(key);
  return {{"type", "object"}, {"properties", std::move(properties)}, {"required", required}};
}

json array_of(json items) {
  return {{"type", "array"}, {"items", std::move(items)}};
}

json time_schema() {
  json t = object_of({{"sec", typed("integer")}, {"nsec", typed("integer")}});
  t["title"] = "time";
  return t;
}

json duration_schema() {
  json d = object_of({{"sec", typed("integer")}, {"nsec", typed("integer")}});
  d["title"] = "duration";
  return d;
}

json xyz_schema() {
  return object_of({{"x", typed("number")}, {"y", typed("number")}, {"z", typed("number")}});
}

json quaternion_schema() {
  return object_of({{"x", typed("number")},
                    {"y", typed("number")},
                    {"z", typed("number")},
                    {"w", typed("number")}});
}

json pose_schema() {
  return object_of({{"position", xyz_schema()}, {"orientation", quaternion_schema()}});
}

json color_schema() {
  return object_of({{"r", typed("number")},
                    {"g", typed("number")},
                    {"b", typed("number")},
                    {"a", typed("number")}});
}

json titled(json schema, const std::string& title) {
  schema["title"] = title;
  return schema;
}

std::string scene_update_schema() {
  const json shape =
      object_of({{"pose", pose_schema()}, {"size", xyz_schema()}, {"color", color_schema()}});
  const json line = object_of({{"type", typed("integer")},
                               {"pose", pose_schema()},
                               {"thickness", typed("number")},
                               {"scale_invariant", typed("boolean")},
                               {"points", array_of(xyz_schema())},
                               {"color", color_schema()},
                               {"colors", array_of(color_schema())},
                               {"indices", array_of(typed("integer"))}});
  const json text = object_of({{"pose", pose_schema()},
                               {"billboard", typed("boolean")},
                               {"font_size", typed("number")},
                               {"scale_invariant", typed("boolean")},
                               {"color", color_schema()},
                               {"text", typed("string")}});
  // Kinds of primitive skyfuse never sends: always empty arrays.
  const json unused = array_of(typed("object"));
  const json entity = object_of(
      {{"timestamp", time_schema()},
       {"frame_id", typed("string")},
       {"id", typed("string")},
       {"lifetime", duration_schema()},
       {"frame_locked", typed("boolean")},
       {"metadata", array_of(object_of({{"key", typed("string")}, {"value", typed("string")}}))},
       {"arrows", unused},
       {"cubes", array_of(shape)},
       {"spheres", array_of(shape)},
       {"cylinders", unused},
       {"lines", array_of(line)},
       {"triangles", unused},
       {"texts", array_of(text)},
       {"models", unused}});
  const json deletion = object_of(
      {{"timestamp", time_schema()}, {"type", typed("integer")}, {"id", typed("string")}});
  return titled(object_of({{"deletions", array_of(deletion)}, {"entities", array_of(entity)}}),
                "foxglove.SceneUpdate")
      .dump();
}

std::string frame_transform_schema() {
  return titled(object_of({{"timestamp", time_schema()},
                           {"parent_frame_id", typed("string")},
                           {"child_frame_id", typed("string")},
                           {"translation", xyz_schema()},
                           {"rotation", quaternion_schema()}}),
                "foxglove.FrameTransform")
      .dump();
}

std::string location_fix_schema() {
  json covariance = array_of(typed("number"));
  covariance["minItems"] = 9;
  covariance["maxItems"] = 9;
  return titled(object_of({{"timestamp", time_schema()},
                           {"frame_id", typed("string")},
                           {"latitude", typed("number")},
                           {"longitude", typed("number")},
                           {"altitude", typed("number")},
                           {"position_covariance", covariance},
                           {"position_covariance_type", typed("integer")}}),
                "foxglove.LocationFix")
      .dump();
}

// What was refused, by whom and why: kind by its summary.json name; the harness is node -1.
json refused_entries(const std::vector<Refusal>& refused) {
  json entries = json::array();
  for (const Refusal& r : refused) {
    entries.push_back({{"node", r.node},
                       {"step", r.step},
                       {"kind", std::string(to_string(r.kind))},
                       {"count", r.count}});
  }
  return entries;
}

std::string round_schema() {
  const json node = object_of({{"node", typed("integer")},
                               {"delivered", typed("boolean")},
                               {"contributors", array_of(typed("integer"))},
                               {"missing", array_of(typed("integer"))}});
  const json refusal = object_of({{"node", typed("integer")},
                                  {"step", typed("integer")},
                                  {"kind", typed("string")},
                                  {"count", typed("integer")}});
  return titled(object_of({{"timestamp", time_schema()},
                           {"step", typed("integer")},
                           {"time_s", typed("number")},
                           {"latency_ms", typed("number")},
                           {"all_inputs_in_time", typed("boolean")},
                           {"measurements", typed("integer")},
                           {"nodes", array_of(node)},
                           {"refused", array_of(refusal)}}),
                "skyfuse.Round")
      .dump();
}

std::string track_error_schema() {
  const json track = object_of({{"node", typed("integer")},
                                {"error_m", typed("number")},
                                {"nees", typed("number")},
                                {"dof", typed("integer")}});
  return titled(object_of({{"timestamp", time_schema()},
                           {"step", typed("integer")},
                           {"tracks", array_of(track)}}),
                "skyfuse.TrackError")
      .dump();
}

std::string modes_schema() {
  const json track =
      object_of({{"node", typed("integer")}, {"probabilities", array_of(typed("number"))}});
  return titled(object_of({{"timestamp", time_schema()},
                           {"step", typed("integer")},
                           {"modes", array_of(typed("string"))},
                           {"tracks", array_of(track)}}),
                "skyfuse.ModeProbabilities")
      .dump();
}

// ---- messages ---------------------------------------------------------------------------

json stamp(std::uint64_t ns) {
  return {{"sec", ns / kNsPerS}, {"nsec", ns % kNsPerS}};
}

json xyz(const Vector3& v) {
  return {{"x", v.x()}, {"y", v.y()}, {"z", v.z()}};
}

json quaternion(const Eigen::Quaterniond& q) {
  return {{"x", q.x()}, {"y", q.y()}, {"z", q.z()}, {"w", q.w()}};
}

json pose(const Vector3& at, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  return {{"position", xyz(at)}, {"orientation", quaternion(q)}};
}

struct Rgba {
  double r, g, b, a;
};
json color(const Rgba& c) {
  return {{"r", c.r}, {"g", c.g}, {"b", c.b}, {"a", c.a}};
}

constexpr Rgba kTruthColor{0.15, 0.70, 0.25, 1.0};
constexpr Rgba kCenterColor{1.00, 0.55, 0.00, 1.0};
constexpr Rgba kPeerColor{0.20, 0.45, 0.90, 1.0};
constexpr Rgba kStationColor{0.45, 0.45, 0.50, 1.0};

json entity(std::uint64_t ns, const std::string& id) {
  return {{"timestamp", stamp(ns)},     {"frame_id", kWorldFrame}, {"id", id},
          {"lifetime", stamp(0)},       {"frame_locked", false},   {"metadata", json::array()},
          {"arrows", json::array()},    {"cubes", json::array()},  {"spheres", json::array()},
          {"cylinders", json::array()}, {"lines", json::array()},  {"triangles", json::array()},
          {"texts", json::array()},     {"models", json::array()}};
}

json shape(const Vector3& at, const Vector3& size, const Rgba& c,
           const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  return {{"pose", pose(at, q)}, {"size", xyz(size)}, {"color", color(c)}};
}

json label(const Vector3& at, const std::string& text, const Rgba& c) {
  return {{"pose", pose(at)},        {"billboard", true}, {"font_size", 14.0},
          {"scale_invariant", true}, {"color", color(c)}, {"text", text}};
}

json line_strip(const std::vector<Vector3>& points, const Rgba& c) {
  json p = json::array();
  for (const Vector3& v : points) p.push_back(xyz(v));
  return {{"type", 0},  // LINE_STRIP
          {"pose", pose(Vector3::Zero())},
          {"thickness", 2.0},
          {"scale_invariant", true},
          {"points", std::move(p)},
          {"color", color(c)},
          {"colors", json::array()},
          {"indices", json::array()}};
}

// The position block of a track's covariance, 3 x 3 (a planar model's height has none).
Eigen::Matrix3d position_covariance(const ReceivedTrack& t, int position_dim) {
  Eigen::Matrix3d p = Eigen::Matrix3d::Zero();
  p.topLeftCorner(position_dim, position_dim) =
      t.estimate.covariance.topLeftCorner(position_dim, position_dim);
  return p;
}

// A sphere primitive scaled and turned into the track's 95 % position ellipsoid.
json ellipsoid(const Vector3& at, const Eigen::Matrix3d& covariance, Rgba c) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  Eigen::Matrix3d axes = eigen.eigenvectors();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);  // a rotation, not a reflection
  Vector3 size;
  for (int i = 0; i < 3; ++i) {
    size(i) = 2.0 * kEllipsoidSigmas * std::sqrt(std::max(eigen.eigenvalues()(i), 0.0));
  }
  c.a = 0.35;
  return shape(at, size, c, Eigen::Quaterniond(axes));
}

// ENU metres from the anchor to latitude, longitude and altitude on WGS-84, with the
// ellipsoid's radii of curvature at the anchor: within millimetres over the few kilometres of a
// scenario.
json location_fix(std::uint64_t ns, const GeoAnchor& anchor, const Vector3& enu,
                  const Eigen::Matrix3d& covariance) {
  constexpr double kA = 6378137.0;
  constexpr double kE2 = 6.69437999014e-3;
  const double phi = anchor.latitude_deg * M_PI / 180.0;
  const double w = 1.0 - kE2 * std::sin(phi) * std::sin(phi);
  const double prime_vertical = kA / std::sqrt(w);
  const double meridian = kA * (1.0 - kE2) / (w * std::sqrt(w));
  json cov = json::array();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) cov.push_back(covariance(r, c));
  }
  return {
      {"timestamp", stamp(ns)},
      {"frame_id", kWorldFrame},
      {"latitude", anchor.latitude_deg + enu.y() / (meridian + anchor.altitude_m) * 180.0 / M_PI},
      {"longitude",
       anchor.longitude_deg +
           enu.x() / ((prime_vertical + anchor.altitude_m) * std::cos(phi)) * 180.0 / M_PI},
      {"altitude", anchor.altitude_m + enu.z()},
      {"position_covariance", std::move(cov)},
      {"position_covariance_type", 3}};  // KNOWN
}

}  // namespace

RunChannels::RunChannels(const RunRecorder& recorder, std::uint64_t epoch_ns)
    : recorder_(recorder), epoch_ns_(epoch_ns), trails_(2 + recorder.station_ids().size()) {
  specs_ = {{"/scene", "foxglove.SceneUpdate", scene_update_schema()},
            {"/stations", "foxglove.SceneUpdate", scene_update_schema()},
            {"/tf", "foxglove.FrameTransform", frame_transform_schema()},
            {"/center/location", "foxglove.LocationFix", location_fix_schema()},
            {"/truth/location", "foxglove.LocationFix", location_fix_schema()},
            {"/skyfuse/round", "skyfuse.Round", round_schema()},
            {"/skyfuse/track_error", "skyfuse.TrackError", track_error_schema()},
            {"/skyfuse/summary", "skyfuse.RunSummary",
             titled(typed("object"), "skyfuse.RunSummary").dump()}};
  if (!recorder.mode_names().empty()) {
    specs_.push_back({"/skyfuse/modes", "skyfuse.ModeProbabilities", modes_schema()});
  }
}

std::uint64_t RunChannels::log_time_ns(std::uint64_t step) const {
  const double dt_ns = recorder_.plan().scenario.time_step_s * 1e9;
  return epoch_ns_ + static_cast<std::uint64_t>(std::llround(static_cast<double>(step) * dt_ns));
}

std::vector<ChannelMessage> RunChannels::round_messages(const RoundRecord& round, Detail detail) {
  RoundView r{round, log_time_ns(round.step), recorder_.truth_position(round.step), {}};
  if (round.central) r.tracks.emplace_back(kCenterNodeId, &*round.central);
  for (std::size_t i = 0; i < round.peers.size(); ++i) {
    if (round.peers[i]) r.tracks.emplace_back(recorder_.station_ids()[i], &*round.peers[i]);
  }
  std::vector<ChannelMessage> out;
  // The trails take a point every kTrailEvery steps, drawn or not.
  extend_trails(round);
  if (detail != Detail::kFiguresOnly) {
    scene_messages(r, scenes_ == 0 || (detail == Detail::kEveryRound && trails_unsent_), out);
  }
  figure_messages(r, out);
  return out;
}

void RunChannels::scene_messages(const RoundView& r, bool with_trails,
                                 std::vector<ChannelMessage>& out) {
  const auto emit = [&](Channel channel, const json& message) {
    out.push_back({channel, r.ns, message.dump()});
  };
  const std::uint64_t ns = r.ns;
  const RoundRecord& round = r.round;
  const Vector3& truth = r.truth;
  const std::vector<int>& ids = recorder_.station_ids();
  const int pd = recorder_.position_dim();
  // The scene: truth, and each track's position and ellipsoid, and the trails.
  json entities = json::array();
  {
    json e = entity(ns, "truth");
    e["spheres"].push_back(shape(truth, Vector3::Constant(1.0), kTruthColor));
    entities.push_back(std::move(e));
  }
  for (const auto& [node, track] : r.tracks) {
    const Vector3 at = recorder_.position_of(*track);
    const Rgba c = node == kCenterNodeId ? kCenterColor : kPeerColor;
    json e = entity(ns, node == kCenterNodeId ? "center" : fmt::format("station/{}", node));
    e["spheres"].push_back(shape(at, Vector3::Constant(0.6), c));
    e["spheres"].push_back(ellipsoid(at, position_covariance(*track, pd), c));
    entities.push_back(std::move(e));
  }
  if (with_trails) {
    trails_unsent_ = false;
    for (std::size_t t = 0; t < trails_.size(); ++t) {
      if (trails_[t].points.size() < 2) continue;
      const std::string id = t == 0   ? "trail/truth"
                             : t == 1 ? "trail/center"
                                      : fmt::format("trail/station/{}", ids[t - 2]);
      json e = entity(ns, id);
      e["lines"].push_back(line_strip(trails_[t].points, t == 0   ? kTruthColor
                                                         : t == 1 ? kCenterColor
                                                                  : kPeerColor));
      entities.push_back(std::move(e));
    }
  }
  emit(kScene, {{"deletions", json::array()}, {"entities", std::move(entities)}});

  if (scenes_++ % kStationsEvery == 0) {
    json sites = json::array();
    for (int id : ids) {
      const StationConfig& s = *recorder_.plan().participant(id);
      json e = entity(ns, fmt::format("site/{}", id));
      e["cubes"].push_back(shape(s.position_m, Vector3::Constant(4.0), kStationColor));
      e["texts"].push_back(label(s.position_m + Vector3(0.0, 0.0, 6.0),
                                 fmt::format("{} ({})", id, s.sensor.kind), kStationColor));
      sites.push_back(std::move(e));
    }
    emit(kStations, {{"deletions", json::array()}, {"entities", std::move(sites)}});
  }

  const GeoAnchor& anchor = recorder_.plan().scenario.anchor;
  if (round.central) {
    const Vector3 at = recorder_.position_of(*round.central);
    emit(kTransforms, {{"timestamp", stamp(ns)},
                       {"parent_frame_id", kWorldFrame},
                       {"child_frame_id", "center_track"},
                       {"translation", xyz(at)},
                       {"rotation", quaternion(Eigen::Quaterniond::Identity())}});
    emit(kCenterLocation, location_fix(ns, anchor, at, position_covariance(*round.central, pd)));
  }
  emit(kTruthLocation, location_fix(ns, anchor, truth, Eigen::Matrix3d::Zero()));
}

void RunChannels::figure_messages(const RoundView& r, std::vector<ChannelMessage>& out) const {
  const auto emit = [&](Channel channel, const json& message) {
    out.push_back({channel, r.ns, message.dump()});
  };
  const RoundRecord& round = r.round;
  const std::uint64_t ns = r.ns;
  const std::vector<int>& ids = recorder_.station_ids();
  const int pd = recorder_.position_dim();

  // Who contributed to each node's track, and who is missing from it.
  json nodes = json::array();
  const auto node_entry = [&](int node, const std::optional<ReceivedTrack>& track) {
    json missing = json::array();
    if (track) {
      for (int id : ids) {
        if (!std::binary_search(track->contributors.begin(), track->contributors.end(), id)) {
          missing.push_back(id);
        }
      }
    }
    nodes.push_back({{"node", node},
                     {"delivered", track.has_value()},
                     {"contributors", track ? json(track->contributors) : json::array()},
                     {"missing", track ? missing : json(ids)}});
  };
  node_entry(kCenterNodeId, round.central);
  for (std::size_t i = 0; i < round.peers.size(); ++i) node_entry(ids[i], round.peers[i]);
  const auto measurements = std::count_if(round.measurements.begin(), round.measurements.end(),
                                          [](const auto& z) { return z.has_value(); });
  emit(kRounds,
       {{"timestamp", stamp(ns)},
        {"step", round.step},
        {"time_s", static_cast<double>(round.step) * recorder_.plan().scenario.time_step_s},
        {"latency_ms", std::chrono::duration<double, std::milli>(round.latency).count()},
        {"all_inputs_in_time", round.all_inputs_in_time},
        {"measurements", measurements},
        {"nodes", std::move(nodes)},
        {"refused", refused_entries(round.refused)}});

  // Each track's position error and position NEES against the truth (chi-square, pd dof).
  json errors = json::array();
  for (const auto& [node, track] : r.tracks) {
    const Eigen::VectorXd e = (r.truth - recorder_.position_of(*track)).head(pd);
    const Eigen::MatrixXd p = track->estimate.covariance.topLeftCorner(pd, pd);
    errors.push_back(
        {{"node", node}, {"error_m", e.norm()}, {"nees", e.dot(p.ldlt().solve(e))}, {"dof", pd}});
  }
  emit(kTrackErrors,
       {{"timestamp", stamp(ns)}, {"step", round.step}, {"tracks", std::move(errors)}});

  if (!recorder_.mode_names().empty()) {
    json probabilities = json::array();
    for (const auto& [node, track] : r.tracks) {
      probabilities.push_back(
          {{"node", node},
           {"probabilities", std::vector<double>(track->mode_probabilities.data(),
                                                 track->mode_probabilities.data() +
                                                     track->mode_probabilities.size())}});
    }
    json names = json::array();
    for (std::string_view n : recorder_.mode_names()) names.push_back(std::string(n));
    emit(kModes, {{"timestamp", stamp(ns)},
                  {"step", round.step},
                  {"modes", std::move(names)},
                  {"tracks", std::move(probabilities)}});
  }
}

void RunChannels::follow(const RoundRecord& round) {
  extend_trails(round);
}

void RunChannels::extend_trails(const RoundRecord& round) {
  if (round.step % kTrailEvery != 0) return;
  const auto extend = [&](Trail& trail, const Vector3& p) {
    trail.points.push_back(p);
    if (trail.points.size() > kTrailPoints) trail.points.erase(trail.points.begin());
  };
  trails_unsent_ = true;
  extend(trails_[0], recorder_.truth_position(round.step));
  if (round.central) extend(trails_[1], recorder_.position_of(*round.central));
  for (std::size_t i = 0; i < round.peers.size(); ++i) {
    if (round.peers[i]) extend(trails_[2 + i], recorder_.position_of(*round.peers[i]));
  }
}

ChannelMessage RunChannels::summary_message(std::string summary_json) const {
  const auto steps = static_cast<std::uint64_t>(recorder_.plan().scenario.steps);
  return {kSummary, log_time_ns(steps), std::move(summary_json)};
}

}  // namespace skyfuse::harness
