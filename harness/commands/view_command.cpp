#include "commands/view_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "report/output_files.hpp"
#include "skyfuse/live/live_server.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {

void add_view_command(CLI::App& app, ViewOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "view", "Serve a recording (skyfuse run --record) in skyfuse's page, until Ctrl-C");
  cmd->add_option("recording", o.recording, "The MCAP file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--address", o.address, "Address to listen on")->capture_default_str();
  cmd->add_option("--port", o.port, "Port to listen on (0: any free port)")->capture_default_str();
}

int run_view(const ViewOptions& o) {
  const std::filesystem::path site = executable_dir() / "view";
  if (!std::filesystem::exists(site / "index.html")) {
    throw std::runtime_error("the page is not built (" + site.string() +
                             "): run npm ci --prefix view, then build again");
  }
  live::LiveServer::Options options;
  options.address = o.address;
  options.port = o.port;
  options.site_dir = site.string();
  options.files["/recording.mcap"] = std::filesystem::absolute(o.recording).string();
  const live::LiveServer server(options, {});
  fmt::print("view: http://{}:{}/?recording=recording.mcap  ({}; Ctrl-C ends)\n", o.address,
             server.port(), o.recording);
  std::fflush(stdout);
  while (!transport::shutdown_requested()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return 0;
}

}  // namespace skyfuse::harness
