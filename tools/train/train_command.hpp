#pragma once
/// \file
/// What `skyfuse-train` does once its command line is parsed: build the data set, train,
/// report each epoch (stdout and an optional CSV), write the weights file.

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>

#include "skyfuse/experiments/paper001/dataset.hpp"
#include "train_mode.hpp"

namespace skyfuse::train {

struct CommandOptions {
  paper001::Network network = paper001::Network::kErrorCompensation;
  Mode mode = Mode::kSmoke;
  std::string out;
  std::string log;  ///< CSV per epoch; empty: none
  std::optional<std::uint64_t> seed;
  std::optional<int> paths;
  std::optional<int> max_epochs;
  std::optional<int> patience;
  std::optional<paper001::WindowFrame> frame;  ///< default: the preset's
  int threads = 1;
};

/// Returns the process exit status; throws on I/O failures.
int run_train_command(const CommandOptions& options, std::ostream& out);

}  // namespace skyfuse::train
