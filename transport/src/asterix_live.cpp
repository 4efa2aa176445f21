#include "skyfuse/transport/asterix_live.hpp"

#include <fmt/format.h>

#include <optional>

namespace skyfuse::transport {
namespace {

std::optional<asterix::UdpEndpoint> group_of(const asterix::UdpEndpoint& listen) {
  if (asterix::is_multicast(listen)) return listen;
  return std::nullopt;
}

}  // namespace

LiveScans::LiveScans(const asterix::UdpEndpoint& listen, std::chrono::milliseconds wait,
                     const Scenario& scenario, const StationConfig& station)
    : feed_("--asterix-in", scenario, station),
      receiver_(listen.port, group_of(listen)),
      receive_buffer_(receiver_.request_receive_buffer(kReceiveBufferOctets)),
      wait_(wait),
      receiving_([this] { receive_until_stopped(); }) {}

LiveScans::~LiveScans() {
  stop_ = true;
  receiving_.join();
}

void LiveScans::receive_until_stopped() {
  // The poll's timeout bounds how long the destructor waits for this thread.
  constexpr int kPollMs = 50;
  while (!stop_) {
    const auto datagram = receiver_.receive(kPollMs);
    if (!datagram) continue;
    {
      const std::lock_guard lock(mutex_);
      feed_.take(*datagram, first_open_);
    }
    arrived_.notify_all();
  }
}

Scan LiveScans::scan_at(std::uint64_t k, const DetectionNoise& noise) {
  std::unique_lock lock(mutex_);
  const bool passed = arrived_.wait_for(lock, wait_, [&] {
    const auto latest = feed_.latest_round();
    return latest && *latest > k;
  });
  if (!passed) ++waited_out_;
  first_open_ = k + 1;
  return feed_.take_scan(k, noise);
}

std::size_t LiveScans::waited_out() const {
  const std::lock_guard lock(mutex_);
  return waited_out_;
}

std::size_t LiveScans::late() const {
  const std::lock_guard lock(mutex_);
  return feed_.late();
}

std::size_t LiveScans::datagrams() const {
  const std::lock_guard lock(mutex_);
  return feed_.datagrams();
}

std::string LiveScans::started() const {
  return fmt::format(
      "station {} takes its scans from a live feed on port {} (receive buffer {} octets), "
      "waiting at most {} ms for the feed to pass a round",
      feed_.station_id(), receiver_.port(), receive_buffer_, wait_.count());
}

std::string LiveScans::summary() const {
  const std::lock_guard lock(mutex_);
  return fmt::format(
      "station {}'s live feed on port {} (receive buffer {} octets): {} datagrams, {} detections "
      "fused, {} records late, {} rounds taken when the wait ran out, {} refused, {} skipped",
      feed_.station_id(), receiver_.port(), receive_buffer_, feed_.datagrams(), feed_.detections(),
      feed_.late(), waited_out_, feed_.refusals().total(), feed_.skipped());
}

}  // namespace skyfuse::transport
