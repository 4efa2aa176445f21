#include "skyfuse/registry/part_info.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "skyfuse/models/height_band.hpp"
#include "skyfuse/models/state_position.hpp"
#include "skyfuse/picture/fixes_position.hpp"
#include "skyfuse/registry/filter_info.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/scenario/scenario.hpp"

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

template <typename Sensor>
constexpr int other_receivers_of() {
  if constexpr (requires { Sensor::kReceivers; }) {
    return Sensor::kReceivers - 1;
  } else {
    return 0;
  }
}

template <template <int> class... Sensors>
std::vector<SensorInfo> describe(SensorList<Sensors...> /*list*/) {
  return {
      SensorInfo{Sensors<kAnyStateDim>::kKind, Sensors<kAnyStateDim>::kMeasDim,
                 Sensors<kAnyStateDim>::kJacobianCols, Sensors<kAnyStateDim>::kNeedsSite,
                 std::vector<std::string_view>(Sensors<kAnyStateDim>::kComponents.begin(),
                                               Sensors<kAnyStateDim>::kComponents.end()),
                 FixesPosition<Sensors<kAnyStateDim>>, other_receivers_of<Sensors<kAnyStateDim>>(),
                 TakesHeightBand<Sensors<kAnyStateDim>>, position_dim<Sensors<kAnyStateDim>>()}...};
}

// Whether a filter part's station turns one detection into one increment by an increment rule.
template <typename Filter>
constexpr bool kHasIncrementRule = requires {
  typename Filter::IncrementRule;
};

template <typename... Filters>
std::vector<FilterInfo> describe(FilterList<Filters...> /*list*/) {
  return {FilterInfo{
      Filters::kKind, Filters::kSummary, Filters::kMotionModel, Filters::kSensor,
      Filters::kOneSensorKind, Filters::kTakesRefusionLag, Filters::kTakesNisGate,
      std::vector<std::string_view>(Filters::kModeNames.begin(), Filters::kModeNames.end()),
      Filters::kNodesTakeTree, Filters::kNeesDof,
      // A picture of many aircraft: parts with an increment rule, and the IMM (its modes).
      kHasIncrementRule<Filters> || !Filters::kModeNames.empty(),
      // A weighed association (JPDA's): a station's contributions must add up, as increments do.
      kHasIncrementRule<Filters>}...};
}

// Each kind once, in registry order.
template <typename Info>
std::string kinds_of(const std::vector<Info>& infos) {
  std::vector<std::string_view> kinds;
  for (const Info& info : infos) {
    if (std::ranges::find(kinds, info.kind) == kinds.end()) kinds.push_back(info.kind);
  }
  return fmt::format("{}", fmt::join(kinds, ", "));
}

template <typename Info>
std::optional<Info> find_kind(std::vector<Info> infos, std::string_view kind) {
  for (Info& info : infos) {
    if (info.kind == kind) return std::move(info);
  }
  return std::nullopt;
}

}  // namespace

std::vector<MotionModelInfo> motion_model_infos() {
  return describe(MotionModels{});
}
std::vector<SensorInfo> sensor_infos() {
  return describe(Sensors{});
}

std::optional<MotionModelInfo> find_motion_model(std::string_view kind) {
  return find_kind(motion_model_infos(), kind);
}

std::optional<SensorInfo> find_sensor(std::string_view kind) {
  return find_kind(sensor_infos(), kind);
}

std::vector<FilterInfo> filter_infos() {
  return describe(FilterParts{});
}

std::optional<FilterInfo> find_filter(std::string_view kind) {
  return find_kind(filter_infos(), kind);
}

std::optional<FilterInfo> find_filter(const FilterConfig& filter) {
  std::optional<FilterInfo> found;
  visit_filter_part<FilterParts>(filter.kind, filter.imm.modes,
                                 [&]<typename Filter>(std::type_identity<Filter>) {
                                   found = describe(FilterList<Filter>{}).front();
                                 });
  return found;
}

std::string filter_mode_sets(std::string_view kind) {
  std::vector<std::string> sets;
  for (const FilterInfo& info : filter_infos()) {
    if (info.kind == kind) sets.push_back(fmt::format("[{}]", fmt::join(info.mode_names, ", ")));
  }
  return fmt::format("{}", fmt::join(sets, ", "));
}

std::string filter_kinds() {
  return kinds_of(filter_infos());
}

std::optional<std::string> filter_option_refusal(const FilterInfo& filter, std::size_t refusion_lag,
                                                 bool nis_gate) {
  if (refusion_lag != 0 && !filter.takes_refusion_lag) {
    return fmt::format("--refusion-lag: filter {} fuses each round once; leave it at 0",
                       filter.kind);
  }
  if (nis_gate && !filter.takes_nis_gate) {
    return fmt::format("--nis-gate: filter {} takes no NIS gate ({})", filter.kind, filter.summary);
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
