#pragma once
// JSON for the channels Foxglove, Lichtblick and skyfuse's own page draw: the foxglove.* schemas
// for the fields skyfuse fills, under the names the tools know, and builders for their messages
// (scene entities and their primitives, location fixes), shared by a run of one aircraft
// (run_channels.hpp) and of many (picture_channels.hpp).

#include <Eigen/Geometry>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse::harness::foxglove {

using nlohmann::json;

inline constexpr std::uint64_t kNsPerS = 1'000'000'000;
inline constexpr const char* kWorldFrame = "world";
/// A 95 % region of a 3-D Gaussian: sqrt of the chi-square(3) 0.95 quantile (7.8147).
inline constexpr double kEllipsoidSigmas = 2.7955;

// ---- JSON schemas ----------------------------------------------------------------------------

json typed(const char* type);
/// An object whose every property is required.
json object_of(json properties);
json array_of(json items);
json time_schema();
json titled(json schema, const std::string& title);
std::string scene_update_schema();
std::string frame_transform_schema();
std::string location_fix_schema();
/// skyfuse.Round: who delivered and who is missing in a round (the page's strip and slider).
std::string round_schema();
/// skyfuse.RunSummary: a run's summary.json as it is, one object at the end of the recording.
std::string run_summary_schema();

// ---- messages --------------------------------------------------------------------------------

struct Rgba {
  double r, g, b, a;
};
/// What both kinds of run draw alike: the truth (an aircraft) and the stations.
inline constexpr Rgba kTruthColor{0.15, 0.70, 0.25, 1.0};
inline constexpr Rgba kStationColor{0.45, 0.45, 0.50, 1.0};

json stamp(std::uint64_t ns);
json xyz(const Vector3& v);
json quaternion(const Eigen::Quaterniond& q);
json pose(const Vector3& at, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity());
json color(const Rgba& c);
/// A scene entity `id` at log time `ns`, with no primitive yet.
json entity(std::uint64_t ns, const std::string& id);
json shape(const Vector3& at, const Vector3& size, const Rgba& c,
           const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity());
json label(const Vector3& at, const std::string& text, const Rgba& c);
json line_strip(const std::vector<Vector3>& points, const Rgba& c);
/// A sphere primitive scaled and turned into the 95 % ellipsoid of a position covariance.
json ellipsoid(const Vector3& at, const Eigen::Matrix3d& covariance, Rgba c);
/// A foxglove.LocationFix of ENU position `enu` (metres from `anchor`), on WGS-84.
json location_fix(std::uint64_t ns, const GeoAnchor& anchor, const Vector3& enu,
                  const Eigen::Matrix3d& covariance);

}  // namespace skyfuse::harness::foxglove
