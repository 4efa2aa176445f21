#pragma once
// The IMM picture's steps (picture/imm_picture_steps.hpp) of the registry's IMM mode set
// number SKYFUSE_IMM_SET for every picture sensor: each imm_picture_steps_<n>.cpp defines that
// number and includes this file, so that one file holds one mode set's steps.

#include <cstddef>
#include <tuple>
#include <type_traits>
#include <variant>

#include "skyfuse/picture/imm_picture_steps.hpp"
#include "skyfuse/picture/picture_sensor.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/tracking/imm_network_impl.hpp"
#include "skyfuse/validation/nis_gate.hpp"

namespace skyfuse {

template <typename Set, typename Sensor>
OwnContribution ImmPictureSteps<Set, Sensor>::contribute(const Peer& state,
                                                         const StationObservation<Sensor>& o,
                                                         typename Peer::Contribution& out) {
  return state.contribute(o, NisGate{}, out);
}

template <typename Set, typename Sensor>
NumericalStatus ImmPictureSteps<Set, Sensor>::update(
    Central& state, std::span<const StationObservation<Sensor>> observations) {
  return state.update(observations);
}

namespace detail {

// The mode sets of the IMM parts of `List`, in its order, as a tuple's types.
template <typename List>
struct ImmSetsOf;
template <typename... Filters>
struct ImmSetsOf<FilterList<Filters...>> {
  template <typename Filter>
  struct One {
    using type = std::tuple<>;
  };
  template <typename Set>
  struct One<ImmFilterPart<Set>> {
    using type = std::tuple<Set>;
  };
  using type = decltype(std::tuple_cat(std::declval<typename One<Filters>::type>()...));
};

using ImmSets = typename ImmSetsOf<FilterParts>::type;
using ImmPictureSensor = PictureSensor<KinematicState::kDim>;

}  // namespace detail

// A new IMM mode set in the registry needs its imm_picture_steps_<n>.cpp (core/CMakeLists.txt),
// a new picture sensor its line below.
static_assert(std::tuple_size_v<detail::ImmSets> == 3,
              "every IMM mode set of the registry has its imm_picture_steps_<n>.cpp");
static_assert(std::variant_size_v<detail::ImmPictureSensor> == 5,
              "every picture sensor has its line below");
template struct ImmPictureSteps<std::tuple_element_t<SKYFUSE_IMM_SET, detail::ImmSets>,
                                std::variant_alternative_t<0, detail::ImmPictureSensor>>;
template struct ImmPictureSteps<std::tuple_element_t<SKYFUSE_IMM_SET, detail::ImmSets>,
                                std::variant_alternative_t<1, detail::ImmPictureSensor>>;
template struct ImmPictureSteps<std::tuple_element_t<SKYFUSE_IMM_SET, detail::ImmSets>,
                                std::variant_alternative_t<2, detail::ImmPictureSensor>>;
template struct ImmPictureSteps<std::tuple_element_t<SKYFUSE_IMM_SET, detail::ImmSets>,
                                std::variant_alternative_t<3, detail::ImmPictureSensor>>;
template struct ImmPictureSteps<std::tuple_element_t<SKYFUSE_IMM_SET, detail::ImmSets>,
                                std::variant_alternative_t<4, detail::ImmPictureSensor>>;

}  // namespace skyfuse
