#pragma once
/// \file
/// A station's scans from a live UDP feed of ASTERIX (`--asterix-in HOST:PORT`): a thread
/// receives every datagram as it comes and keeps the CAT048 plots or CAT021 reports of the
/// station's own data source by round (scan_feed.hpp); the station, opening round k, takes the
/// round's records once the feed has passed it — a record of a later round from the network's
/// own area (SAC), of any station, has come — or once `wait` has gone by, with what came. A record
/// of a round already taken is late: counted, not fused. The feed's time of day is the run's time
/// (a run starts at midnight of the feed's day, as `--asterix-record` writes it).

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "skyfuse/asterix/udp.hpp"
#include "skyfuse/transport/fed_scans.hpp"
#include "skyfuse/transport/scan_feed.hpp"

namespace skyfuse::transport {

class LiveScans final : public FedScans {
 public:
  /// Listens on `listen`'s port, joining it where it is a multicast group, for `station`'s
  /// records. Throws as ScanFeed does, and std::runtime_error where the socket cannot be
  /// opened.
  LiveScans(const asterix::UdpEndpoint& listen, std::chrono::milliseconds wait,
            const Scenario& scenario, const StationConfig& station);
  ~LiveScans() override;
  LiveScans(const LiveScans&) = delete;
  LiveScans& operator=(const LiveScans&) = delete;

  Scan scan_at(std::uint64_t k, const DetectionNoise& noise) override;
  std::string started() const override;
  std::string summary() const override;

  std::uint16_t port() const { return receiver_.port(); }
  /// The receive buffer the system granted (kReceiveBufferOctets asked).
  std::size_t receive_buffer() const { return receive_buffer_; }

  /// Twenty rounds of a feed at a large system's scale (4 000 reports, some 180 000 octets, in a
  /// burst each round): what a station busy fusing may have to hold.
  static constexpr std::size_t kReceiveBufferOctets = 4U << 20U;
  /// Rounds taken before the feed had passed them: the wait ran out.
  std::size_t waited_out() const;
  std::size_t late() const;
  std::size_t datagrams() const;

 private:
  void receive_until_stopped();

  ScanFeed feed_;  // guarded by mutex_; first, so that a sensor it refuses binds no socket
  asterix::UdpReceiver receiver_;
  std::size_t receive_buffer_;
  std::chrono::milliseconds wait_;
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::uint64_t first_open_ = 0;  // guarded: the rounds before it are taken
  std::size_t waited_out_ = 0;    // guarded
  std::atomic<bool> stop_{false};
  std::thread receiving_;  // last: it starts once the rest is made
};

}  // namespace skyfuse::transport
