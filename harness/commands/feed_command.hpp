#pragma once
// `skyfuse feed FILE.pcap --to HOST:PORT`: sends the UDP datagrams of a recorded ASTERIX feed
// (say an --asterix-record of a run) to a destination at the pace they were captured, as the
// sensors sent them — what stations started with `--asterix-in` listen to.

#include <CLI/App.hpp>
#include <cstdint>
#include <optional>
#include <string>

namespace skyfuse::harness {

struct FeedOptions {
  std::string file;
  std::string destination;                   ///< HOST:PORT
  double speed = 1.0;                        ///< 2: twice as fast as captured
  std::optional<std::uint16_t> source_port;  ///< only the datagrams sent from this port
  double lead_s = 0.0;  ///< the captured times shifted this much earlier: the feed runs ahead
};

void add_feed_command(CLI::App& app, FeedOptions& options);
int run_feed(const FeedOptions& options);

}  // namespace skyfuse::harness
