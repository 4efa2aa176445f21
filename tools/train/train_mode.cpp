#include "train_mode.hpp"

#include <stdexcept>

namespace skyfuse::train {

std::string mode_name(Mode mode) {
  switch (mode) {
    case Mode::kSmoke:
      return "smoke";
    case Mode::kReduced:
      return "reduced";
    case Mode::kFull:
      return "full";
  }
  throw std::logic_error("skyfuse-train: unknown mode");
}

std::string network_name(paper001::Network network) {
  return network == paper001::Network::kErrorCompensation ? "ec" : "se";
}

}  // namespace skyfuse::train
