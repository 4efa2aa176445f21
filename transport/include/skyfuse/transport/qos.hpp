#pragma once
/// \file
/// Every QoS skyfuse uses, chosen in one place (src/qos.cpp explains each choice), and the
/// hook through which a user replaces any of it without rebuilding: a Fast DDS XML file whose
/// profiles carry these names takes precedence over the built-in choice.
///
///   participant profile          skyfuse_participant
///   data writer / reader         <topic>_writer / <topic>_reader, e.g. skyfuse_increment_reader
///
/// The file comes from --qos FILE, or from FASTDDS_DEFAULT_PROFILES_FILE as Fast DDS reads it.
///
/// With the built-in participant (UDP on 127.0.0.1), the one-to-many topics - ticks,
/// measurements, increments - reach their readers by UDP multicast: one datagram per write
/// instead of one per matched reader. A user's participant profile brings its own transport,
/// and then every topic stays unicast unless the user's reader profiles say otherwise.

#include <cstdint>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "skyfuse/options/network_options.hpp"

namespace eprosima::fastdds::dds {
class Publisher;
class Subscriber;
}  // namespace eprosima::fastdds::dds

namespace skyfuse::transport {

/// Largest station count the resource limits are sized for (the wire types allow as many).
inline constexpr int kMaxStations = 256;

/// Socket receive buffer the built-in participant asks for. The kernel grants at most
/// net.core.rmem_max (208 KiB on a stock Debian 12).
inline constexpr std::uint64_t kReceiveBufferBytes = 4u << 20;

/// net.core.rmem_max, if /proc says; below kReceiveBufferBytes, large runs lose datagrams to
/// full socket buffers and wait for their repair.
std::optional<std::uint64_t> receive_buffer_cap();

/// What to tell the user when a run of `stations` stations needs larger socket buffers than
/// the kernel grants; nothing when it does not.
std::optional<std::string> receive_buffer_warning(int stations);

/// The multicast group of the one-to-many topics and of discovery: the RTPS default group.
inline constexpr const char* kMulticastGroup = "239.255.0.1";

/// The UDP port `topic`'s readers listen on for multicast in `domain_id`; none for the topics
/// that stay unicast (one reader, or a low rate). Each such topic has a port of its own so
/// that a process receives only the topics it reads.
std::optional<int> multicast_port(std::string_view topic, int domain_id);

/// The QoS profile of a writer of a picture's tracks on `skyfuse_track`: a track an instance,
/// the latest sample of each kept for a reader that joins late.
inline constexpr const char* kPictureTrackProfile = "skyfuse_picture_track";
/// The most tracks such a writer holds at once (a picture's tracks; a dropped track's place is
/// freed when its writer unregisters it).
inline constexpr int kMaxPictureTracks = 16384;

class QosProfiles {
 public:
  /// Loads `xml_file` if given; a file that does not load is an error, not a silent default.
  /// `best_effort_data`: the data links (increments, measurements) are BEST_EFFORT.
  /// `domain_id` places the multicast ports. `network`: the built-in participant's interface
  /// and discovery; `serves_discovery`: it is the discovery server at
  /// network.discovery_server, not a client.
  QosProfiles(const std::optional<std::filesystem::path>& xml_file, bool best_effort_data,
              int domain_id, options::NetworkOptions network = {}, bool serves_discovery = false);

  /// True when the built-in participant discovers by multicast, and with it the one-to-many
  /// topics travel by multicast; false when a `skyfuse_participant` profile replaces it or a
  /// discovery server is used (where multicast may not reach).
  bool multicast() const { return !user_participant_ && !network_.discovery_server; }

  eprosima::fastdds::dds::DomainParticipantQos participant(const std::string& name) const;
  /// A writer's QoS by its profile: the topic's name, or kPictureTrackProfile. An XML profile
  /// named `<profile>_writer` replaces the built-in one.
  eprosima::fastdds::dds::DataWriterQos writer(const eprosima::fastdds::dds::Publisher& publisher,
                                               const std::string& profile) const;
  eprosima::fastdds::dds::DataReaderQos reader(const eprosima::fastdds::dds::Subscriber& subscriber,
                                               const std::string& topic) const;

 private:
  // Makes `qos` announce itself to network.discovery_peers only.
  void announce_to_peers_only(eprosima::fastdds::dds::DomainParticipantQos& qos) const;
  // Makes `qos` the discovery server at `server`, or a client of it.
  void use_discovery_server(eprosima::fastdds::dds::DomainParticipantQos& qos,
                            const options::Ipv4Endpoint& server) const;

  bool best_effort_data_;
  int domain_id_;
  options::NetworkOptions network_;
  bool serves_discovery_;
  // The user's `skyfuse_participant` profile, read once; none: the built-in participant.
  std::optional<eprosima::fastdds::dds::DomainParticipantQos> user_participant_;
};

}  // namespace skyfuse::transport
