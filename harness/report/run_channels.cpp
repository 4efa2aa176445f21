#include "report/run_channels.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "report/foxglove_json.hpp"

namespace skyfuse::harness {
namespace {

using namespace foxglove;  // NOLINT(google-build-using-namespace): this file's vocabulary

constexpr Rgba kCenterColor{1.00, 0.55, 0.00, 1.0};
constexpr Rgba kPeerColor{0.20, 0.45, 0.90, 1.0};

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

// The position block of a track's covariance, 3 x 3 (a planar model's height has none).
Eigen::Matrix3d position_covariance(const ReceivedTrack& t, int position_dim) {
  Eigen::Matrix3d p = Eigen::Matrix3d::Zero();
  p.topLeftCorner(position_dim, position_dim) =
      t.estimate.covariance.topLeftCorner(position_dim, position_dim);
  return p;
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
            {"/skyfuse/summary", "skyfuse.RunSummary", run_summary_schema()}};
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
