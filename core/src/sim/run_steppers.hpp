#pragma once
// Which in-process twin steps a run of each registered filter part: a part with an increment
// rule needs no line (IncrementRunStepper); the EKF (its center stacks), the IMM and the NCRKF
// have their own. A stepper runs the peers' fused filter and the center's on the same
// measurements, by the round rule the processes follow (monte_carlo.cpp drives it).

#include "sim/ekf_run_stepper.hpp"
#include "sim/imm_run_stepper.hpp"
#include "sim/increment_run_stepper.hpp"
#include "sim/ncrkf_run_stepper.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/tracking/increment_rules.hpp"

namespace skyfuse {

template <typename Filter, typename Model, template <int> class SensorOf>
struct RunStepperOf {
  using type = IncrementRunStepper<Model, SensorOf, typename Filter::IncrementRule>;
};
template <typename Model, template <int> class SensorOf>
struct RunStepperOf<EkfFilterPart, Model, SensorOf> {
  using type = EkfRunStepper<Model, SensorOf>;
};
template <typename ModeSet, typename Model, template <int> class SensorOf>
struct RunStepperOf<ImmFilterPart<ModeSet>, Model, SensorOf> {
  using type = ImmRunStepper<ModeSet, SensorOf>;
};
template <typename Model, template <int> class SensorOf>
struct RunStepperOf<NcrkfFilterPart, Model, SensorOf> {
  using type = NcrkfRunStepper;
};
}  // namespace skyfuse
