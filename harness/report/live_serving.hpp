#pragma once
// `skyfuse run --live` for either kind of run: the server's options (the endpoint, and
// skyfuse's page where it is installed beside the executable), the line that tells the user
// where to look, and the lines that say how the stream went once the run is over.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>

#include "run/run_options.hpp"
#include "skyfuse/live/live_server.hpp"

namespace skyfuse::harness {

/// The live server on `endpoint`, serving skyfuse's page when it is installed.
live::LiveServer::Options live_server_options(const LiveEndpoint& endpoint);

/// "live: ws://ADDRESS:PORT (Foxglove), http://ADDRESS:PORT/ (page)" on stdout, at once.
void announce_live(const LiveEndpoint& endpoint, std::uint16_t port);

/// Ends the stream of `feed` (a LiveFeedOf<...>) with the run's summary, and says what it sent.
template <typename Feed>
void finish_live(Feed& feed, std::string summary_json) {
  feed.finish(std::move(summary_json));
  const live::LiveServer::Stats stats = feed.stats();
  fmt::print("live: {} message(s) sent, {} client(s) connected at the end\n", stats.frames_sent,
             stats.clients);
  if (const auto dropped = stats.clients_dropped; dropped > 0) {
    fmt::print("live: {} client(s) dropped for falling behind\n", dropped);
  }
  if (feed.rounds_dropped() > 0) {
    spdlog::warn("live: {} round(s) not streamed: the stream fell more than {} rounds behind",
                 feed.rounds_dropped(), Feed::kMaxWaitingRounds);
  }
}

}  // namespace skyfuse::harness
