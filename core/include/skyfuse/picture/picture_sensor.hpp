#pragma once
/// \file
/// A picture's station carries its sensor as a value: one of the registered sensors one of whose
/// detections fixes a position (fixes_position.hpp), for an N-entry state. The picture's code is
/// written once over the tracks' filter and motion model; where a sensor's arithmetic is needed
/// (a pair's innovation, a detection's fix, a station's contribution) the station's sensor is
/// visited and its own fixed-size code runs, so a picture of one sensor kind computes the bits a
/// picture typed by that sensor did, and stations of different kinds can share a picture.
///
/// A new sensor that fixes a position joins by its line in the registry (registry.hpp).

#include <algorithm>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "skyfuse/core/index_constant.hpp"
#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/picture/fixes_position.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/registry/registry.hpp"

namespace skyfuse {

namespace detail {

// The sensors of `List` that fix a position, each for an N-entry state, as a tuple's types.
template <int N, typename List>
struct PositionFixingSensors;
template <int N, template <int> class... S>
struct PositionFixingSensors<N, SensorList<S...>> {
  using type = decltype(std::tuple_cat(
      std::declval<std::conditional_t<FixesPosition<S<N>>, std::tuple<S<N>>, std::tuple<>>>()...));
};

template <typename Tuple>
struct PictureSensorTypes;
template <typename... S>
struct PictureSensorTypes<std::tuple<S...>> {
  using Sensor = std::variant<S...>;
  using Observation = std::variant<StationObservation<S>...>;
  using ObservationBuffers = std::tuple<std::vector<StationObservation<S>>...>;
  template <template <typename> class F>
  using Each = std::tuple<F<S>...>;
  static constexpr int kMaxMeasDim = std::max({S::kMeasDim...});
};

template <int N>
using PictureSensorTypesOf = PictureSensorTypes<typename PositionFixingSensors<N, Sensors>::type>;

}  // namespace detail

/// A picture station's sensor, for an N-entry state: which registered sensor, and where.
template <int N>
using PictureSensor = typename detail::PictureSensorTypesOf<N>::Sensor;
/// One detection of a station, with its sensor and noise, as the sensor's own observation.
template <int N>
using PictureObservation = typename detail::PictureSensorTypesOf<N>::Observation;
/// A list of observations per sensor kind (reused storage for by_sensor_kind).
template <int N>
using PictureObservationBuffers = typename detail::PictureSensorTypesOf<N>::ObservationBuffers;
/// F<S> for each picture sensor S of an N-entry state, in a tuple.
template <int N, template <typename> class F>
using ForEachPictureSensor = typename detail::PictureSensorTypesOf<N>::template Each<F>;
/// The picture's sensors as a pack (registry/sensor_pack.hpp) for code that takes stations of
/// several kinds at once (fusion/mixed_stacked_ekf.hpp).
template <int N>
struct PictureSensorPack {
  static constexpr int kStateDim = N;
  using Observation = PictureObservation<N>;
};

static_assert(detail::PictureSensorTypesOf<kKinematicsDim>::kMaxMeasDim <= kMaxDetectionDim,
              "a picture's sensor reports more values than a Detection holds");

/// Calls f(std::type_identity<S>{}) for each sensor S of `Variant`'s alternatives, in order.
template <typename Variant, typename F>
void for_each_alternative(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (f(std::type_identity<std::variant_alternative_t<I, Variant>>{}), ...);
  }
  (std::make_index_sequence<std::variant_size_v<Variant>>{});
}

/// The picture's sensor kinds, "range_azimuth_elevation, position_velocity", for a message.
inline std::string picture_sensor_names() {
  std::string names;
  for_each_alternative<PictureSensor<kKinematicsDim>>([&]<typename S>(std::type_identity<S>) {
    names += (names.empty() ? "" : ", ") + std::string(S::kKind);
  });
  return names;
}

/// Station `station`'s sensor, for an N-entry state. Throws std::invalid_argument when its kind
/// is not a picture's.
template <int N>
PictureSensor<N> make_picture_sensor(const StationConfig& station) {
  std::optional<PictureSensor<N>> made;
  for_each_alternative<PictureSensor<N>>([&]<typename S>(std::type_identity<S>) {
    if (!made && S::kKind == station.sensor.kind) made.emplace(make_sensor<S>(station));
  });
  if (!made) {
    throw std::invalid_argument("station " + std::to_string(station.id) + ": sensor '" +
                                station.sensor.kind + "' is none of a picture's (" +
                                picture_sensor_names() + ")");
  }
  return *made;
}

/// The number of values a detection of `sensor` holds.
template <int N>
int measurement_dim(const PictureSensor<N>& sensor) {
  return std::visit([](const auto& s) { return std::decay_t<decltype(s)>::kMeasDim; }, sensor);
}

/// Calls one_kind(std::span<const StationObservation<S>>) when every observation of
/// `observations` is of one sensor kind S (copied into that kind's list in `buffers`), and
/// mixed() when they are of several; returns what it returns.
template <int N, typename OneKind, typename Mixed>
auto by_sensor_kind(std::span<const PictureObservation<N>> observations,
                    PictureObservationBuffers<N>& buffers, OneKind&& one_kind, Mixed&& mixed) {
  const std::size_t kind = observations.empty() ? 0 : observations.front().index();
  for (const auto& o : observations) {
    if (o.index() != kind) return mixed();
  }
  constexpr std::size_t kKinds = std::variant_size_v<PictureObservation<N>>;
  return with_index_constant<kKinds>(
      kind, [&]<std::size_t I>(std::integral_constant<std::size_t, I>) {
        using One = std::variant_alternative_t<I, PictureObservation<N>>;
        std::vector<One>& typed = std::get<I>(buffers);
        typed.clear();
        for (const auto& o : observations) typed.push_back(std::get<I>(o));
        return one_kind(std::span<const One>(typed));
      });
}

}  // namespace skyfuse
