#include "report/live_serving.hpp"

#include <filesystem>

#include "report/output_files.hpp"

namespace skyfuse::harness {

live::LiveServer::Options live_server_options(const LiveEndpoint& endpoint) {
  live::LiveServer::Options server;
  server.address = endpoint.address;
  server.port = endpoint.port;
  if (const auto site = executable_dir() / "view"; std::filesystem::exists(site / "index.html")) {
    server.site_dir = site.string();
  }
  return server;
}

void announce_live(const LiveEndpoint& endpoint, std::uint16_t port) {
  fmt::print("live: ws://{0}:{1} (Foxglove), http://{0}:{1}/ (page)\n", endpoint.address, port);
  std::fflush(stdout);
}

}  // namespace skyfuse::harness
