#include "report/foxglove_json.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "skyfuse/traffic/geodesy.hpp"

namespace skyfuse::harness::foxglove {

// ---- JSON schemas ----------------------------------------------------------------------------

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

std::string run_summary_schema() {
  return titled(typed("object"), "skyfuse.RunSummary").dump();
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

json stamp(std::uint64_t ns) {
  return {{"sec", ns / kNsPerS}, {"nsec", ns % kNsPerS}};
}

json xyz(const Vector3& v) {
  return {{"x", v.x()}, {"y", v.y()}, {"z", v.z()}};
}

json quaternion(const Eigen::Quaterniond& q) {
  return {{"x", q.x()}, {"y", q.y()}, {"z", q.z()}, {"w", q.w()}};
}

json pose(const Vector3& at, const Eigen::Quaterniond& q) {
  return {{"position", xyz(at)}, {"orientation", quaternion(q)}};
}

json color(const Rgba& c) {
  return {{"r", c.r}, {"g", c.g}, {"b", c.b}, {"a", c.a}};
}

json entity(std::uint64_t ns, const std::string& id) {
  return {{"timestamp", stamp(ns)},     {"frame_id", kWorldFrame}, {"id", id},
          {"lifetime", stamp(0)},       {"frame_locked", false},   {"metadata", json::array()},
          {"arrows", json::array()},    {"cubes", json::array()},  {"spheres", json::array()},
          {"cylinders", json::array()}, {"lines", json::array()},  {"triangles", json::array()},
          {"texts", json::array()},     {"models", json::array()}};
}

json shape(const Vector3& at, const Vector3& size, const Rgba& c, const Eigen::Quaterniond& q) {
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

json location_fix(std::uint64_t ns, const GeoAnchor& anchor, const Vector3& enu,
                  const Eigen::Matrix3d& covariance) {
  const Vector3 geodetic = from_local_enu(anchor, enu);  // WGS-84, traffic/geodesy.hpp
  json cov = json::array();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) cov.push_back(covariance(r, c));
  }
  return {{"timestamp", stamp(ns)},       {"frame_id", kWorldFrame},
          {"latitude", geodetic.x()},     {"longitude", geodetic.y()},
          {"altitude", geodetic.z()},     {"position_covariance", std::move(cov)},
          {"position_covariance_type", 3}};  // KNOWN
}

}  // namespace skyfuse::harness::foxglove
