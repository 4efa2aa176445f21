#pragma once
// What a station fuses for each registered filter part. Each fusion takes the station's own
// measurement to its contribution, checks its peers' samples and fuses a round
// (station_process.cpp's round loop moves the samples). A part with an increment rule needs no
// line here: SingleModelFusion sums its increments. The IMM and the NCRKF have their own.

#include "imm_fusion.hpp"
#include "ncrkf_fusion.hpp"
#include "single_model_fusion.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/tracking/increment_rules.hpp"

namespace skyfuse::station {

template <typename Filter, typename Model, typename Sensor>
struct StationFusionOf {
  using type = SingleModelFusion<Model, Sensor, typename Filter::IncrementRule>;
};
template <typename ModeSet, typename Model, typename Sensor>
struct StationFusionOf<ImmFilterPart<ModeSet>, Model, Sensor> {
  using type = ImmFusion<ModeSet, Sensor>;
};
template <typename Model, typename Sensor>
struct StationFusionOf<NcrkfFilterPart, Model, Sensor> {
  using type = NcrkfFusion;
};

}  // namespace skyfuse::station
