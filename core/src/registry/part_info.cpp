#include "skyfuse/registry/part_info.hpp"

#include <fmt/format.h>

#include "skyfuse/models/state_position.hpp"
#include "skyfuse/registry/registry.hpp"

namespace skyfuse {
namespace {

template <typename... Models>
std::vector<MotionModelInfo> describe(ModelList<Models...> /*list*/) {
  return {MotionModelInfo{
      Models::kKind, Models::kDim,
      std::vector<std::string_view>(Models::kNoiseFields.begin(), Models::kNoiseFields.end()),
      position_dim<Models>()}...};
}

// Sensor<N> for an N large enough for any sensor: the constants do not depend on N.
constexpr int kAnyStateDim = 64;

template <template <int> class... Sensors>
std::vector<SensorInfo> describe(SensorList<Sensors...> /*list*/) {
  return {SensorInfo{Sensors<kAnyStateDim>::kKind, Sensors<kAnyStateDim>::kMeasDim,
                     Sensors<kAnyStateDim>::kJacobianCols, Sensors<kAnyStateDim>::kNeedsSite,
                     std::vector<std::string_view>(Sensors<kAnyStateDim>::kComponents.begin(),
                                                   Sensors<kAnyStateDim>::kComponents.end())}...};
}

template <typename Info>
std::string kinds_of(const std::vector<Info>& infos) {
  std::string out;
  for (const Info& info : infos) out += (out.empty() ? "" : ", ") + std::string(info.kind);
  return out;
}

}  // namespace

std::vector<MotionModelInfo> motion_model_infos() {
  return describe(MotionModels{});
}
std::vector<SensorInfo> sensor_infos() {
  return describe(Sensors{});
}

std::optional<MotionModelInfo> find_motion_model(std::string_view kind) {
  for (MotionModelInfo& info : motion_model_infos()) {
    if (info.kind == kind) return std::move(info);
  }
  return std::nullopt;
}

std::optional<SensorInfo> find_sensor(std::string_view kind) {
  for (SensorInfo& info : sensor_infos()) {
    if (info.kind == kind) return std::move(info);
  }
  return std::nullopt;
}

std::string motion_model_kinds() {
  return kinds_of(motion_model_infos());
}
std::string sensor_kinds() {
  return kinds_of(sensor_infos());
}

}  // namespace skyfuse
