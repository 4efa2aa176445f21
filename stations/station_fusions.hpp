#pragma once
// What a station fuses for each registered filter part on each motion model. Each fusion has
// the station's sensing (station_sensing.hpp) make its contribution, checks its peers' samples
// and fuses a round (station.hpp's round loop moves the samples). None depends on the sensor:
// a part with an increment rule needs no line here, as SingleModelFusion sums its increments
// whichever rule made them. The IMM and the NCRKF have their own.

#include "imm_fusion.hpp"
#include "ncrkf_fusion.hpp"
#include "single_model_fusion.hpp"
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

}  // namespace skyfuse::station
