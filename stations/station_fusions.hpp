#pragma once
// What a station fuses for each registered filter part: one line per filter. Each fusion takes
// the station's own measurement to its contribution, checks its peers' samples and fuses a
// round (station_process.cpp moves the samples).

#include "imm_fusion.hpp"
#include "ncrkf_fusion.hpp"
#include "single_model_fusion.hpp"
#include "skyfuse/registry/registry.hpp"

namespace skyfuse::station {

template <typename Filter, typename Model, typename Sensor>
struct StationFusionOf;

template <typename Model, typename Sensor>
struct StationFusionOf<EkfFilterPart, Model, Sensor> {
  using type = SingleModelFusion<Model, Sensor>;
};
template <typename Model, typename Sensor>
struct StationFusionOf<ImmFilterPart, Model, Sensor> {
  using type = ImmFusion<Sensor>;
};
template <typename Model, typename Sensor>
struct StationFusionOf<NcrkfFilterPart, Model, Sensor> {
  using type = NcrkfFusion;
};
template <typename Model, typename Sensor>
struct StationFusionOf<UkfFilterPart, Model, Sensor> {
  using type = SingleModelFusion<Model, Sensor, UnscentedIncrementRule>;
};

}  // namespace skyfuse::station
