// skyfuse-center: the fusion center; the run's filter on every station's raw measurement.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>

#include "center_process.hpp"
#include "skyfuse/transport/node_presence.hpp"
#include "skyfuse/transport/shutdown.hpp"

int main(int argc, char** argv) {
  using namespace skyfuse;
  CLI::App app{"skyfuse-center: the fusion center; the run's filter on all stations' measurements"};
  options::NodeOptions options;
  options::add_node_options(app, options);
  CLI11_PARSE(app, argc, argv);

  spdlog::set_level(spdlog::level::from_str(options.log_level));
  spdlog::set_pattern("[center] %^%l%$: %v");
  transport::install_shutdown_handlers();
  // Every way a node's run ends leaves without deleting its participant (node_presence.hpp).
  transport::leave_without_goodbye(options::run_node([&] { return center::run_center(options); }));
}
