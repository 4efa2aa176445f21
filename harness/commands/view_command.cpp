#include "commands/view_command.hpp"

#include <fmt/format.h>

#include <cctype>
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>

#include "report/output_files.hpp"
#include "report/run_recording.hpp"
#include "skyfuse/live/live_server.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {
namespace {

// The characters a URL carries as they are in a path and a query (RFC 3986's unreserved ones,
// less '~').
bool url_plain(unsigned char c) {
  return std::isalnum(c) || c == '-' || c == '_' || c == '.';
}

// `text` with every other byte percent-encoded, or replaced by `stand_in` when one is given.
std::string url_safe(const std::string& text, std::optional<char> stand_in = std::nullopt) {
  std::string out;
  for (const unsigned char c : text) {
    if (url_plain(c)) {
      out.push_back(static_cast<char>(c));
    } else {
      out += stand_in ? std::string(1, *stand_in) : fmt::format("%{:02X}", c);
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
  const std::string served = url_safe(name, '_');
  options.files["/" + served] = std::filesystem::absolute(o.recording).string();
  const live::LiveServer server(options, {});
  fmt::print("view: http://{}:{}/?recording={}&name={}  ({}; Ctrl-C ends)\n", o.address,
             server.port(), served, url_safe(name), o.recording);
  std::fflush(stdout);
  while (!transport::shutdown_requested()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return 0;
}

}  // namespace skyfuse::harness
