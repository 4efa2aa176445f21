#pragma once
// An increment that passes every content check, of the run's state dimension (the scenario's
// motion model): the start of every sample the rogue forges, so that only the one fault it
// carries (or who sent it) can keep it out.

#include <cstdint>

#include "skyfuse/transport/topics.hpp"

namespace skyfuse::rogue {

/// A range-like information of 1e-4 along x about a prior with mean 0 and P = I, for a state of
/// `state_dim` entries.
wire::InformationIncrement plausible_increment(std::uint64_t run, std::uint32_t step, int station,
                                               int state_dim);

}  // namespace skyfuse::rogue
