// skyfuse-station: one ground station of the peer-to-peer fusion network.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>

#include "skyfuse/transport/node_presence.hpp"
#include "skyfuse/transport/shutdown.hpp"
#include "station_process.hpp"

int main(int argc, char** argv) {
  using namespace skyfuse;
  CLI::App app{"skyfuse-station: one ground station; fuses every station's increments"};
  station::StationOptions options;
  app.add_option("--id", options.id, "Station id (from the scenario)")->required();
  app.add_option("--replay", options.replay_path,
                 "Replay measurements from this CSV instead of simulating them")
      ->check(CLI::ExistingFile);
  app.add_option("--rejoin-at-step", options.rejoin_step,
                 "This process replaces a station that died: start at this step, take the "
                 "peers' track from their first increments, contribute from the next step");
  options::add_node_options(app, options.node);
  CLI11_PARSE(app, argc, argv);

  spdlog::set_level(spdlog::level::from_str(options.node.log_level));
  spdlog::set_pattern(fmt::format("[station {}] %^%l%$: %v", options.id));
  transport::install_shutdown_handlers();
  // Every way a node's run ends leaves without deleting its participant (node_presence.hpp).
  transport::leave_without_goodbye(
      options::run_node([&] { return station::run_station(options); }));
}
