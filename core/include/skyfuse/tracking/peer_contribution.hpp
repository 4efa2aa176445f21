#pragma once
/// \file
/// What a station sends its peers each round: its increment, and the prior it was computed
/// against (see peer_tracker.hpp for why the prior travels with it).

#include "skyfuse/core/types.hpp"
#include "skyfuse/fusion/information_increment.hpp"

namespace skyfuse {

template <int N>
struct PeerContribution {
  InformationIncrement<N> increment;
  GaussianState<N> prior;
};

}  // namespace skyfuse
