#pragma once
/// \file
/// Checks of numeric command-line values that say in words what is allowed. CLI11's own
/// PositiveNumber and NonNegativeNumber are ranges of a double: refusing `--stations 0` or
/// `--steps abc`, they print an upper bound 309 digits long. Include only where CLI11 already is:
/// it brings the whole of CLI11.

#include <CLI/CLI.hpp>  // Validators.hpp alone does not compile in CLI11 2.1
#include <cstdint>

namespace skyfuse::options {

/// A whole number >= `low` ("must be a whole number >= 1, got abc").
CLI::Validator whole_number_at_least(std::int64_t low);
/// A whole number in [low, high].
CLI::Validator whole_number_in(std::int64_t low, std::int64_t high);
/// A finite number > 0.
CLI::Validator positive_number();
/// A finite number >= 0.
CLI::Validator non_negative_number();

/// "A.B.C.D:PORT", an IPv4 address (unicast or a multicast group) and a port, as ASTERIX over
/// UDP takes it (asterix/udp.hpp); the refusal says what is wrong.
CLI::Validator udp_endpoint();

}  // namespace skyfuse::options
