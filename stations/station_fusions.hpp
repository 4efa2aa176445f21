#pragma once
// What a station fuses for each registered filter part on each motion model. Each fusion has
// the station's sensing (station_sensing.hpp) make its contribution, checks its peers' samples
// and fuses a round (station.hpp's round loop moves the samples). None depends on the sensor:
// a part with an increment rule needs no line here, as SingleModelFusion sums its increments
// whichever rule made them. The IMM and the NCRKF have their own.

#include <cstddef>
#include <optional>
#include <type_traits>

#include "imm_fusion.hpp"
#include "ncrkf_fusion.hpp"
#include "single_model_fusion.hpp"
#include "skyfuse/registry/compiled_parts.hpp"
#include "skyfuse/registry/configuration_groups.hpp"
#include "skyfuse/registry/registry.hpp"

namespace skyfuse::station {

template <typename Filter, typename Model>
struct StationFusionOf {
  using type = SingleModelFusion<Model>;
};
template <typename ModeSet, typename Model>
struct StationFusionOf<ImmFilterPart<ModeSet>, Model> {
  using type = ImmFusion<ModeSet>;
};
template <typename Model>
struct StationFusionOf<NcrkfFilterPart, Model> {
  using type = NcrkfFusion;
};

template <typename Filter, typename Model>
using StationFusion = typename StationFusionOf<Filter, Model>::type;

namespace detail {

// The number of the first configuration group of this build whose fusion is `Fusion`.
template <typename Fusion, typename... Filters, typename... Models>
constexpr std::optional<std::size_t> first_group_of_fusion(FilterList<Filters...> /*parts*/,
                                                           ModelList<Models...> /*models*/) {
  std::size_t next = 0;
  std::optional<std::size_t> first;
  const auto each_part = [&]<typename Part>(std::type_identity<Part>) {
    const auto each_model = [&]<typename M>(std::type_identity<M>) {
      if constexpr (filter_runs_on_model<Part, M>()) {
        if (!first && std::is_same_v<StationFusion<Part, M>, Fusion> &&
            filter_part_compiled(Part::kKind)) {
          first = next;
        }
        ++next;
      }
    };
    (each_model(std::type_identity<Models>{}), ...);
  };
  (each_part(std::type_identity<Filters>{}), ...);
  return first;
}

}  // namespace detail

/// Whether the group of `Filter` on `Model` is the first of this build whose fusion is its own.
/// Parts with an increment rule share one fusion per model (the EKF's and the unscented
/// filter's on constant velocity are one SingleModelFusion), so the rounds of each fusion are
/// compiled in that group's shard only (station_rounds_shard.cpp), not in every group's.
template <typename Filter, typename Model>
constexpr bool compiles_its_fusion() {
  return detail::first_group_of_fusion<StationFusion<Filter, Model>>(
             FilterParts{}, MotionModels{}) == kConfigurationGroup<Filter, Model>;
}

}  // namespace skyfuse::station
