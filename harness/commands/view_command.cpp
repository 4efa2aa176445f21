#include "commands/view_command.hpp"

#include <fmt/format.h>

#include <cctype>
#include <chrono>
#include <filesystem>
#include <thread>

#include "report/output_files.hpp"
#include "report/run_recording.hpp"
#include "skyfuse/live/live_server.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {
namespace {

// A file name as a URL's path segment and query value: unreserved characters as they are.
std::string url_encoded(const std::string& text) {
  std::string out;
  for (const unsigned char c : text) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') {
      out.push_back(static_cast<char>(c));
    } else {
      out += fmt::format("%{:02X}", c);
    }
  }
  return out;
}

}  // namespace

void add_view_command(CLI::App& app, ViewOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "view", "Serve a recording (skyfuse run --record) in skyfuse's page, until Ctrl-C");
  cmd->add_option("recording", o.recording, "The MCAP file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--address", o.address, "Address to listen on")->capture_default_str();
  cmd->add_option("--port", o.port, "Port to listen on (0: any free port)")->capture_default_str();
}

int run_view(const ViewOptions& o) {
  check_viewable_recording(o.recording);
  const std::filesystem::path site = executable_dir() / "view";
  if (!std::filesystem::exists(site / "index.html")) {
    throw std::runtime_error("the page is not built (" + site.string() +
                             "): run npm ci --prefix view, then build again");
  }
  live::LiveServer::Options options;
  options.address = o.address;
  options.port = o.port;
  options.site_dir = site.string();
  // Served under its own name (characters a URL path would encode made plain), which the page
  // shows in its header.
  const std::string name = std::filesystem::path(o.recording).filename().string();
  std::string served = name;
  for (char& c : served) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  }
  options.files["/" + served] = std::filesystem::absolute(o.recording).string();
  const live::LiveServer server(options, {});
  fmt::print("view: http://{}:{}/?recording={}&name={}  ({}; Ctrl-C ends)\n", o.address,
             server.port(), served, url_encoded(name), o.recording);
  std::fflush(stdout);
  while (!transport::shutdown_requested()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return 0;
}

}  // namespace skyfuse::harness
