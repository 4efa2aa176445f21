#pragma once
/// \file
/// The modes a network IMM can have, by the name a scenario gives each (filter.imm.modes), and
/// sets of them in order. The registry compiles an IMM filter part for each set it lists
/// (registry.hpp); a scenario's modes must be one of those sets, in its order. Cheap to include:
/// names and types only (tracking/network_imm.hpp builds the filters).

#include <array>
#include <string_view>

#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/coordinated_turn_3d.hpp"

namespace skyfuse {

/// A mode's name in a scenario. A model becomes a mode with a specialisation here, a factory in
/// tracking/network_imm.cpp (make_imm_mode) and its kCommonIndex into KinematicState.
template <typename Model>
struct ImmModeName;
template <>
struct ImmModeName<ConstantVelocity3D> {
  static constexpr std::string_view kName = "constant_velocity";
};
template <>
struct ImmModeName<ConstantAcceleration3D> {
  static constexpr std::string_view kName = "constant_acceleration";
};
template <>
struct ImmModeName<CoordinatedTurn3D> {
  static constexpr std::string_view kName = "coordinated_turn";
};

/// The modes of one IMM, in the order of every probability vector and wire sample it makes.
template <typename... Modes>
struct ImmModeSet {
  static constexpr int kModes = sizeof...(Modes);
  static_assert(kModes >= 2, "an IMM mixes at least two modes");
  static constexpr std::array<std::string_view, kModes> kNames = {ImmModeName<Modes>::kName...};
};

/// The modes of an IMM scenario that names none: CV, the scenario's CA model, CT.
using DefaultImmModes = ImmModeSet<ConstantVelocity3D, ConstantAcceleration3D, CoordinatedTurn3D>;

}  // namespace skyfuse
