#include "skyfuse/options/network_options.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <map>

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
  app.add_option_function<std::vector<std::string>>(
         "--discovery-peers",
         [&options](const std::vector<std::string>& texts) {
           options.discovery_peers.clear();
           for (const std::string& text : texts) {
             const auto endpoint = parse_ipv4_endpoint(text);
             if (!endpoint) {
               throw CLI::ValidationError(
                   "--discovery-peers", "expected ADDRESS:PORT (IPv4, port 1-65535), got " + text);
             }
             options.discovery_peers.push_back(*endpoint);
           }
         },
         "Announce this node only to the participants listening for discovery at these "
         "endpoints, not by multicast: it knows only them and those that list it")
      ->type_name("ADDRESS:PORT,...")
      ->delimiter(',')
      ->excludes("--discovery-server");
  app.add_option_function<int>(
         "--participant-id", [&options](int id) { options.participant_id = id; },
         "This node's RTPS participant id, which fixes its discovery port at 7410 + 250 "
         "domain + 2 id (default: the first free one)")
      ->type_name("N")
      ->check(CLI::Range(0, kParticipantIdsPerAddress - 1));
}

std::string_view discovery_name(Discovery discovery) {
  switch (discovery) {
    case Discovery::kAutomatic:
      return "auto";
    case Discovery::kMulticast:
      return "multicast";
    case Discovery::kServer:
      return "server";
    case Discovery::kPeers:
      return "peers";
  }
  return "auto";
}

CLI::Option* add_discovery_option(CLI::App& app, Discovery& discovery, const std::string& help) {
  const std::map<std::string, Discovery> names{{"auto", Discovery::kAutomatic},
                                               {"multicast", Discovery::kMulticast},
                                               {"server", Discovery::kServer},
                                               {"peers", Discovery::kPeers}};
  return app.add_option("--discovery,--host-discovery", discovery, help)
      ->transform(CLI::CheckedTransformer(names))
      ->option_text(
          fmt::format("auto|multicast|server|peers (default: {})", discovery_name(discovery)));
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
  if (!options.discovery_peers.empty()) {
    std::string peers;
    for (const Ipv4Endpoint& peer : options.discovery_peers) {
      if (!peers.empty()) peers += ',';
      peers += peer.to_string();
    }
    args.push_back("--discovery-peers");
    args.push_back(std::move(peers));
  }
  if (options.participant_id) {
    args.push_back("--participant-id");
    args.push_back(std::to_string(*options.participant_id));
  }
  return args;
}

}  // namespace skyfuse::options
