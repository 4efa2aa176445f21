#include "commands/feed_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <thread>

#include "skyfuse/asterix/pcap_stream.hpp"
#include "skyfuse/asterix/udp.hpp"
#include "skyfuse/options/number_checks.hpp"

namespace skyfuse::harness {

void add_feed_command(CLI::App& app, FeedOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "feed",
      "Send a recorded ASTERIX feed (a pcap of UDP datagrams, say an --asterix-record) to "
      "HOST:PORT at the pace it was captured: what `skyfuse run --asterix-in` listens to");
  cmd->add_option("FILE", o.file, "The pcap to send")->required()->check(CLI::ExistingFile);
  cmd->add_option("--to", o.destination, "Destination: a multicast group or a host, and a port")
      ->required()
      ->check(options::udp_endpoint())
      ->type_name("HOST:PORT");
  cmd->add_option("--speed", o.speed, "Pace: 1 as captured, 2 twice as fast")
      ->check(options::positive_number())
      ->capture_default_str();
  cmd->add_option("--source-port", o.source_port,
                  "Only the datagrams sent from this port (an --asterix-record's scans are sent "
                  "from 8601, its pictures from 8600)");
  cmd->add_option("--lead-s", o.lead_s,
                  "Send every datagram this many captured seconds early, all those within it at "
                  "once: a live station takes a round without waiting once the feed has passed "
                  "it")
      ->check(options::non_negative_number())
      ->capture_default_str();
}

int run_feed(const FeedOptions& o) {
  std::ifstream in(o.file, std::ios::binary);
  if (!in) throw std::invalid_argument(fmt::format("{}: cannot be read", o.file));
  // One datagram in memory at a time: a day's capture is sent as it is read.
  asterix::PcapStream file(in);
  if (file.error()) throw std::invalid_argument(fmt::format("{}: {}", o.file, *file.error()));
  std::string error;
  const auto destination = asterix::parse_udp_endpoint(o.destination, error);
  if (!destination) throw std::invalid_argument("--to: " + error);
  asterix::UdpSender sender(*destination);
  // Captured time t is sent at start + (t - first - lead) / speed.
  const auto start = std::chrono::steady_clock::now();
  std::optional<std::int64_t> first_ns;
  std::size_t octets = 0;
  while (const auto d = file.next()) {
    if (o.source_port && d->source.port != *o.source_port) continue;
    if (!first_ns) first_ns = d->time_ns;
    const double due_s = (static_cast<double>(d->time_ns - *first_ns) * 1e-9 - o.lead_s) / o.speed;
    if (due_s > 0.0) {
      std::this_thread::sleep_until(start + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                                std::chrono::duration<double>(due_s)));
    }
    sender.send(d->payload);
    octets += d->payload.size();
  }
  const double took_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("sent %zu datagrams (%zu octets) to %s in %.1f s; %zu refused by the system\n",
              sender.sent(), octets, o.destination.c_str(), took_s, sender.failed());
  if (file.error()) {
    std::fprintf(stderr, "skyfuse: %s: stopped early: %s\n", o.file.c_str(), file.error()->c_str());
    return 1;
  }
  return sender.failed() == 0 ? 0 : 1;
}

}  // namespace skyfuse::harness
