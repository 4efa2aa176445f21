#pragma once
// `skyfuse view FILE.mcap`: a recording (skyfuse run --record) in skyfuse's own page, with a
// time slider, served on loopback until interrupted.

#include <CLI/App.hpp>
#include <cstdint>
#include <string>

namespace skyfuse::harness {

struct ViewOptions {
  std::string recording;
  std::string address = "127.0.0.1";
  std::uint16_t port = 8765;  ///< 0: any free port
};

void add_view_command(CLI::App& app, ViewOptions& options);
int run_view(const ViewOptions& options);

}  // namespace skyfuse::harness
