#pragma once
// Which in-process twin steps a run of each registered filter part: one line per filter. A
// stepper runs the peers' fused filter and the center's on the same measurements, by the round
// rule the processes follow (monte_carlo.cpp drives it).

#include "sim/ekf_run_stepper.hpp"
#include "sim/imm_run_stepper.hpp"
#include "sim/ncrkf_run_stepper.hpp"
#include "sim/ukf_run_stepper.hpp"
#include "skyfuse/registry/registry.hpp"

namespace skyfuse {

template <typename Filter, typename Model, template <int> class SensorOf>
struct RunStepperOf;

template <typename Model, template <int> class SensorOf>
struct RunStepperOf<EkfFilterPart, Model, SensorOf> {
  using type = EkfRunStepper<Model, SensorOf>;
};
template <typename Model, template <int> class SensorOf>
struct RunStepperOf<ImmFilterPart, Model, SensorOf> {
  using type = ImmRunStepper<SensorOf>;
};
template <typename Model, template <int> class SensorOf>
struct RunStepperOf<NcrkfFilterPart, Model, SensorOf> {
  using type = NcrkfRunStepper;
};
template <typename Model, template <int> class SensorOf>
struct RunStepperOf<UkfFilterPart, Model, SensorOf> {
  using type = UkfRunStepper<Model, SensorOf>;
};

}  // namespace skyfuse
