#include "skyfuse/options/network_options.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <charconv>

namespace skyfuse::options {

std::string Ipv4Endpoint::to_string() const {
  return fmt::format("{}:{}", address, port);
}

bool is_ipv4_address(std::string_view text) {
  // inet_pton takes exactly four decimal parts, each in [0, 255], and nothing around them.
  const std::string copy(text);
  in_addr parsed{};
  return inet_pton(AF_INET, copy.c_str(), &parsed) == 1;
}

std::optional<Ipv4Endpoint> parse_ipv4_endpoint(std::string_view text) {
  const auto colon = text.rfind(':');
  if (colon == std::string_view::npos) return std::nullopt;
  const std::string_view address = text.substr(0, colon);
  const std::string_view digits = text.substr(colon + 1);
  unsigned port = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), port);
  if (error != std::errc() || end != digits.data() + digits.size() || digits.empty() || port == 0 ||
      port > 65535 || !is_ipv4_address(address)) {
    return std::nullopt;
  }
  return Ipv4Endpoint{std::string(address), static_cast<std::uint16_t>(port)};
}

void add_network_options(CLI::App& app, NetworkOptions& options) {
  app.add_option_function<std::string>(
         "--interface",
         [&options](const std::string& text) {
           if (!is_ipv4_address(text)) {
             throw CLI::ValidationError("--interface", "expected an IPv4 address, got " + text);
           }
           options.interface_address = text;
         },
         "IPv4 address of the interface this node's DDS sockets use (default 127.0.0.1: one "
         "host; give the host's own address to reach other hosts)")
      ->type_name("ADDRESS");
  app.add_option_function<std::string>(
         "--discovery-server",
         [&options](const std::string& text) {
           const auto endpoint = parse_ipv4_endpoint(text);
           if (!endpoint) {
             throw CLI::ValidationError("--discovery-server",
                                        "expected ADDRESS:PORT (IPv4, port 1-65535), got " + text);
           }
           options.discovery_server = endpoint;
         },
         "Discover the run's participants through the discovery server at ADDRESS:PORT "
         "instead of by multicast (no multicast at all then); `skyfuse run` serves it itself")
      ->type_name("ADDRESS:PORT");
}

CLI::Option* add_host_discovery_option(CLI::App& app, bool& multicast, const std::string& help) {
  return app
      .add_option_function<std::string>(
          "--host-discovery", [&multicast](const std::string& how) { multicast = how == "multicast"; },
          help)
      ->check(CLI::IsMember({"server", "multicast"}))
      ->default_str(multicast ? "multicast" : "server");
}

std::vector<std::string> network_arguments(const NetworkOptions& options) {
  std::vector<std::string> args;
  if (options.interface_address != NetworkOptions{}.interface_address) {
    args = {"--interface", options.interface_address};
  }
  if (options.discovery_server) {
    args.push_back("--discovery-server");
    args.push_back(options.discovery_server->to_string());
  }
  return args;
}

}  // namespace skyfuse::options
