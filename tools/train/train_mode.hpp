#pragma once
/// \file
/// How much `skyfuse-train` trains (lstm_trainer.hpp's presets), apart from libtorch so that
/// the command line (main.cpp) compiles without it.

#include <string>

#include "skyfuse/experiments/paper001/dataset.hpp"

namespace skyfuse::train {

enum class Mode { kSmoke, kReduced, kFull };

std::string mode_name(Mode mode);
std::string network_name(paper001::Network network);

}  // namespace skyfuse::train
