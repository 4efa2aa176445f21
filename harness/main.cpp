// skyfuse: the harness. Parses the command line and hands over to one command.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "sweep_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"skyfuse: ground-station aircraft tracking, central vs peer-to-peer fusion"};
  app.require_subcommand(1);
  skyfuse::harness::SweepOptions sweep;
  skyfuse::harness::add_sweep_command(app, sweep);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (app.got_subcommand("sweep"))
      return skyfuse::harness::run_sweep(sweep);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "skyfuse: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
