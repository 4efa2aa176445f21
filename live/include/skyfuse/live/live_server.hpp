#pragma once
// `skyfuse run --live [ADDRESS:]PORT`: a Foxglove WebSocket server (ws_protocol.hpp) that
// streams a run's channels while it goes on, and answers plain HTTP on the same port with
// skyfuse's own page. It only publishes. publish() never blocks the caller: messages go to the
// server's own thread, and a client that falls more than `client_buffer_bytes` behind is
// dropped rather than waited for.
//
// The WebSocket library (websocketpp) stays inside live_server.cpp: it builds only as C++17.

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "skyfuse/live/ws_protocol.hpp"

namespace skyfuse::live {

class LiveServer {
 public:
  struct Options {
    std::string address = "127.0.0.1";  ///< loopback unless another address is given
    std::uint16_t port = 8765;          ///< 0: any free port (tests)
    std::size_t client_buffer_bytes = std::size_t{8} << 20;
    std::string site_dir;  ///< files served over HTTP from "/"; empty: a one-line page
    /// More files served over HTTP: URL path ("/recording.mcap") -> file on disk.
    std::map<std::string, std::string> files;
  };
  struct Stats {
    std::size_t clients = 0;            ///< connected now
    std::uint64_t clients_dropped = 0;  ///< for reading too slowly
    std::uint64_t frames_sent = 0;
    std::uint64_t requests_refused = 0;  ///< client messages answered with a status and ignored
  };

  /// Listens and starts serving; throws std::runtime_error naming ADDRESS:PORT if it cannot.
  LiveServer(Options options, std::vector<AdvertisedChannel> channels);
  ~LiveServer();  ///< closes every connection and stops
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  std::uint16_t port() const;  ///< the port listened on (the one chosen, for port 0)
  struct Message {
    std::uint32_t channel = 0;
    std::uint64_t log_time_ns = 0;
    std::string payload;
  };
  /// Sends each message to every client subscribed to its channel. One hand-over to the
  /// server's thread for the lot: a caller batching its messages wakes that thread once.
  void publish(std::vector<Message> messages);
  /// Whether any client is subscribed to anything now: when not, a caller need not build
  /// messages at all.
  bool has_subscribers() const;
  /// Waits up to `timeout_ms` for everything published so far to be handed to the clients'
  /// sockets; true if it was.
  bool flush(int timeout_ms);
  Stats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace skyfuse::live
