#pragma once
// A classic pcap file read one datagram at a time (pcap.hpp tells what frames it takes): what a
// recording too long to hold at once needs — `skyfuse feed` and a station replaying a day's
// capture keep one frame in memory, not the file. read_pcap reads the same way, into a vector.

#include <cstdint>
#include <istream>
#include <optional>
#include <span>
#include <string>

#include "skyfuse/asterix/pcap.hpp"

namespace skyfuse::asterix {

/// Whether a file's first four octets are a pcap's magic number (classic, either byte order,
/// micro- or nanosecond stamps) or pcapng's, which PcapStream refuses by name: a file that
/// does not start so is something else (raw ASTERIX blocks, say).
bool starts_like_pcap(std::span<const std::uint8_t> first);

class PcapStream {
 public:
  /// Reads the file header from `in`, which must outlive the stream; error() says why where
  /// it is no pcap this reads (pcapng, another link type, too short).
  explicit PcapStream(std::istream& in);

  /// The next UDP datagram; nullopt at the end of the file, or where a record cannot be read
  /// (a record header or a frame past the end: error() then says which). Frames that hold no
  /// datagram this reads are skipped and counted in skipped().
  std::optional<UdpDatagram> next();

  const PcapSkips& skipped() const { return skipped_; }
  const std::optional<std::string>& error() const { return error_; }

 private:
  bool fail(std::string why);

  std::istream& in_;
  bool swapped_ = false;
  bool nanoseconds_ = false;
  std::uint32_t link_ = 0;
  Bytes frame_;
  PcapSkips skipped_;
  std::optional<std::string> error_;
};

}  // namespace skyfuse::asterix
