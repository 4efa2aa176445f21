// skyfuse-station: one ground station of the peer-to-peer fusion network.
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <vector>

#include "skyfuse/transport/node_presence.hpp"
#include "skyfuse/transport/shutdown.hpp"
#include "station_process.hpp"

int main(int argc, char** argv) {
  using namespace skyfuse;
  CLI::App app{"skyfuse-station: one ground station; fuses every station's increments"};
  station::StationOptions options;
  std::vector<int> ids;
  app.add_option(
         "--id", ids,
         "Station id (from the scenario). Given several times, this process runs those "
         "stations, each on a thread of its own, sharing one DDS participant (simulation on "
         "one host; runs of one aircraft)")
      ->required();
  app.add_option("--replay", options.replay_path,
                 "Replay measurements from this CSV instead of simulating them")
      ->check(CLI::ExistingFile);
  app.add_option("--rejoin-at-step", options.rejoin_step,
                 "This process replaces a station that died: start at this step, take the "
                 "peers' track from their first increments, contribute from the next step");
  options::add_node_options(app, options.node);
  CLI11_PARSE(app, argc, argv);

  spdlog::set_level(spdlog::level::from_str(options.node.log_level));
  spdlog::set_pattern(
      fmt::format("[station{} {}] %^%l%$: %v", ids.size() > 1 ? "s" : "", fmt::join(ids, ",")));
  transport::install_shutdown_handlers();
  // Every way a node's run ends leaves without deleting its participant (node_presence.hpp).
  transport::leave_without_goodbye(
      options::run_node([&] { return station::run_stations(options, ids); }));
}
