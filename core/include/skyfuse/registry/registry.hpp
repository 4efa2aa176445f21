#pragma once
/// \file
/// The parts a scenario can name, and the types that implement them. This file is the one place
/// where a new motion model, sensor or filter becomes known to the scenario loader, the
/// measurement simulation, the sample checks, the in-process Monte Carlo and the processes: add
/// its header below and its type to the list.
///
/// A motion model is a class with kKind, kDim, kNoiseFields, NoiseStd, from_kinematics(),
/// propagate(), jacobian() (or propagate_covariance()) and process_noise(). A sensor is a class
/// template over the state dimension with kKind, kMeasDim, kJacobianCols, kNeedsSite,
/// kComponents, predict(), jacobian(), residual(), to_reported() and check_reported(). Every
/// 3-D model keeps the position in state entries 0-2 and the velocity in 3-5, which is what the
/// sensors read. A filter part (filters/parts/) states the models and sensors it runs on and
/// the options it refuses. See docs/extending.md.

#include "skyfuse/filters/parts/ekf_part.hpp"
#include "skyfuse/filters/parts/imm_part.hpp"
#include "skyfuse/filters/parts/ncrkf_part.hpp"
#include "skyfuse/filters/parts/ukf_part.hpp"
#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/multilateration.hpp"
#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth.hpp"
#include "skyfuse/models/range_azimuth_altitude.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/models/state_position.hpp"
#include "skyfuse/models/tdoa/range_difference_sensor.hpp"
#include "skyfuse/models/tdoa/tdoa_relative_motion.hpp"
#include "skyfuse/registry/part_lists.hpp"
#include "skyfuse/registry/sensor_pack.hpp"
#include "skyfuse/tracking/imm_modes.hpp"

namespace skyfuse {

using MotionModels = ModelList<ConstantAcceleration3D, ConstantVelocity3D, TdoaRelativeMotion>;
using Sensors = SensorList<RangeAzimuthElevation, PositionVelocity, RangeDifferenceSensor,
                           Multilateration, RangeAzimuthAltitude, RangeAzimuth>;

/// The IMM is one part per set of modes it is compiled for (tracking/imm_modes.hpp); a scenario
/// picks one by its filter.imm.modes.
using FilterParts =
    FilterList<EkfFilterPart, ImmFilterPart<DefaultImmModes>,
               ImmFilterPart<ImmModeSet<ConstantVelocity3D, CoordinatedTurn3D>>,
               ImmFilterPart<ImmModeSet<ConstantVelocity3D, ConstantAcceleration3D>>,
               NcrkfFilterPart, UkfFilterPart>;

/// Stations with different sensors in one run: any registered sensor, for an N-entry state.
template <int N>
using AnySensor = typename PackOfList<N, Sensors>::type;

/// Whether `Filter` runs on motion model `Model` (with some station).
template <typename Filter, typename Model>
constexpr bool filter_runs_on_model() {
  return Filter::kMotionModel.empty() || Filter::kMotionModel == Model::kKind;
}

/// Whether filter part `Filter` runs on `Model` with stations of `Sensor` (one sensor type, or a
/// SensorPack when their kinds differ), by what the part states of itself.
/// Only the combinations where the model keeps the position the sensor reads are compiled: a
/// 3-D radar on paper 002's [dx, dy, d_t1, ...] is not (a horizontal TDOA receiver on a 3-D
/// model is: it reads the first two entries). Mixed stations may hold any sensor, so a 3-D model.
template <typename Filter, typename Model, typename Sensor>
constexpr bool filter_runs_on() {
  if (!filter_runs_on_model<Filter, Model>()) return false;
  if constexpr (IsSensorPack<Sensor>::value) {
    return !Filter::kOneSensorKind && Filter::kSensor.empty() && position_dim<Model>() == 3;
  } else {
    return (Filter::kSensor.empty() || Filter::kSensor == Sensor::kKind) &&
           position_dim<Sensor>() <= position_dim<Model>();
  }
}

}  // namespace skyfuse
