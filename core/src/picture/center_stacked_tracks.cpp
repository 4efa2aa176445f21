// The EKF center's stacked update of a track's detections (picture/track_filters.hpp),
// once for each motion model of the registry.
#include <span>
#include <type_traits>
#include <variant>

#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/registry/registry.hpp"

namespace skyfuse {

template <typename Model>
bool CenterStackedTracks<Model>::update(State& state,
                                        std::span<const PictureObservation<kDim>> observations,
                                        std::span<const double> /*weights*/) {
  State updated = state;
  const UpdateReport report = by_sensor_kind<kDim>(
      observations, buffers_,
      [&]<typename Sensor>(std::span<const StationObservation<Sensor>> one_kind) {
        return std::get<StackedEkf<kDim, Sensor>>(stacked_).update(updated, one_kind);
      },
      [&] { return mixed_.update(updated, observations); });
  if (report.status != NumericalStatus::kOk) return false;
  state = updated;
  return true;
}

// A new motion model in the registry needs its line below.
static_assert(
    std::is_same_v<MotionModels,
                   ModelList<ConstantAcceleration3D, ConstantVelocity3D, TdoaRelativeMotion>>,
    "every motion model of the registry has its CenterStackedTracks below");
template class CenterStackedTracks<ConstantAcceleration3D>;
template class CenterStackedTracks<ConstantVelocity3D>;
template class CenterStackedTracks<TdoaRelativeMotion>;

}  // namespace skyfuse
