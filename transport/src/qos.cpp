#include "skyfuse/transport/qos.hpp"

#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <fmt/format.h>

#include <fastdds/dds/core/policy/QosPolicies.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "skyfuse/options/node_options.hpp"

namespace skyfuse::transport {
namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::Duration_t;

namespace {

// Lock-step rounds need every sample: one lost increment stalls a round. So every data topic
// is RELIABLE with KEEP_ALL history (KEEP_LAST drops samples in a burst, and says so only in
// sample_lost_status), and the resource limits are sized for kMaxStations stations with a few
// steps in flight. The defaults would lose data silently: a reader is BEST_EFFORT by default,
// max_instances is 10.
// At 4 steps in flight (1 024 samples) the bare floor's tick and echo writers, 6 000 writes/s with
// a 100 ms heartbeat, filled their history under a loaded core and write() timed out (4 of 4
// `skyfuse bench --stations 1` runs beside a busy loop; 0 of 6 at 32). Samples are allocated as
// they are needed: a station's peak memory stays 21-22 MiB.
constexpr int kStepsInFlight = 32;
constexpr int kMaxSamples = kMaxStations * kStepsInFlight;

// A writer heartbeats while a sample is unacknowledged and every heartbeat draws an ACKNACK from
// each reader, so the period is paid in receptions: at 20 ms, lock-step M = 64 (tree, reliable,
// 500 steps, alternating pairs) received 1 315-1 505 datagrams a round and ran 23.6-32.7
// rounds/s; at 100 ms, 626-821 and 30.7-58.6. M = 4: wall time 0.999 of the 20 ms build's, CPU
// 0.95 (farm-bench, 8 pairs). A lost datagram now waits up to 100 ms for its repair instead of 20
// (the default would stall 3 s): inside a lock-step round's deadline; a real-time round's 15 ms
// never waited for one. The writer keeps its samples until acknowledged, so the history below
// holds 100 ms of the fastest writer's samples with room to spare (kStepsInFlight). Tracks had
// 100 ms before the data topics did: at 20 ms nearly every track cost three datagrams (DATA,
// HEARTBEAT, ACKNACK; M = 64, tree, best effort, real time, tcpdump over 5 s: 13 heartbeats and
// 13 acknowledgements a round, against 233 data samples).
const Duration_t kHeartbeatPeriod{0, 100'000'000};
// Fast DDS arms a per-reader nack-suppression timer on every write; at the default of 0 it
// expires at once, so every write woke the participant's event thread (and that thread then
// queued on the writer's mutex): ~3 wake-ups per station per round. A 10 ms window keeps the
// timer armed across the writes of several rounds. `skyfuse run --steps 3000`, two runs each:
// context switches per round M = 4 66-75 -> 50-54, M = 8 139-141 -> 110-111. The price: a NACK
// that arrives within 10 ms of the DATA it asks for is ignored, and the next heartbeat repairs.
const Duration_t kNackSuppression{0, 10'000'000};
// write() gives up after this; every write is checked, so a stuck reader becomes an error.
const Duration_t kMaxBlockingTime{2, 0};

// Status announcements are durable (TRANSIENT_LOCAL, last value per writer) so that a reader
// that joins late - the harness, a second station with the same id - still learns the state.
bool is_status_topic(const std::string& topic) {
  return topic == "skyfuse_status";
}

// Tracks, pictures and statuses are keyed by their source (wire types: @key), one instance each,
// and durable: a reader that joins late - a viewer, a client of another DDS implementation -
// gets each source's latest track at once, also from a station that has gone silent.
bool is_track_topic(const std::string& topic) {
  return topic == "skyfuse_track" || topic == "skyfuse_picture_round";
}
// A picture's tracks on skyfuse_track: up to kMaxPictureTracks instances a writer, the last
// sample of each. At 64 a track (the single track's depth) a node of a 1 000-aircraft picture
// would keep 64 000 samples of up to 2.3 KB for late joiners.
bool is_picture_track_profile(const std::string& profile) {
  return profile == kPictureTrackProfile;
}
bool is_keyed_topic(const std::string& topic) {
  return is_status_topic(topic) || is_track_topic(topic) || is_picture_track_profile(topic);
}
// A source's instances: its live and its settled tracks, or its status. The center is source 0.
constexpr int kMaxInstances = 2 * (kMaxStations + 1);
// Per instance, a keyed reader holds at most this many samples not yet taken (a reliable writer
// then waits for it), and a track writer keeps this many for late joiners: 1.3 s of tracks at
// dt = 0.02 s. A reliable KEEP_LAST writer drops its oldest sample even if unacknowledged, so
// the depth is also how far the harness may fall behind a station before a track is lost.
constexpr int kSamplesPerInstance = 64;
// At the end of a run a station sends its last --refusion-lag settled tracks at once: they must
// fit in the settled instance's history together.
static_assert(kSamplesPerInstance >= static_cast<int>(options::kMaxRefusionLag));

// A whole picture a peer takes (skyfuse_picture_state): only the latest counts, and it must
// reach a reader its writer matched only after writing it. A restarted station joins once its
// own endpoints have matched its peers', which may match its reader later: under load a
// picture sent in that gap was lost and the station took one only rounds later.
bool is_latest_state_topic(const std::string& topic) {
  return topic == "skyfuse_picture_state";
}

// The links fusion tolerates losing: a round closes at its deadline without the sample.
bool is_data_link_topic(const std::string& topic) {
  return topic == "skyfuse_increment" || topic == "skyfuse_partial" ||
         topic == "skyfuse_measurement" || topic == "skyfuse_picture_scan" ||
         topic == "skyfuse_picture_bundle";
}

// The RTPS port mapping (options::kRtpsPortBase, kRtpsDomainGain) gives domain d its
// user-multicast port at 7401 + 250 d and its first unicast port at 7410 + 250 d; the ports
// between are never used by it, and the one-to-many topics take theirs from there.
constexpr int kFirstFreeOffset = 2;

}  // namespace

std::optional<std::uint64_t> receive_buffer_cap() {
  std::ifstream file("/proc/sys/net/core/rmem_max");
  std::uint64_t bytes = 0;
  if (file >> bytes) return bytes;
  return std::nullopt;
}

std::optional<std::string> receive_buffer_warning(int stations) {
  // Drops were measured from 20 stations on (M = 16: none).
  constexpr int kStationsThatOverflow = 20;
  const auto cap = receive_buffer_cap();
  if (stations < kStationsThatOverflow || !cap || *cap >= kReceiveBufferBytes) return std::nullopt;
  return fmt::format(
      "net.core.rmem_max is {} bytes, below the {} the DDS nodes ask for: with {} stations, "
      "datagrams will overflow the socket buffers and wait for their repair (as root: sysctl -w "
      "net.core.rmem_max={})",
      *cap, kReceiveBufferBytes, stations, kReceiveBufferBytes);
}

std::optional<int> multicast_port(std::string_view topic, int domain_id) {
  // Ticks go to every node, measurements to the center and the harness's recorder, increments
  // and the picture's scans to every station. Tracks have one reader, statuses are few:
  // unicast.
  constexpr std::string_view kOneToMany[] = {"skyfuse_tick", "skyfuse_measurement",
                                             "skyfuse_increment", "skyfuse_picture_scan"};
  for (int i = 0; i < static_cast<int>(std::size(kOneToMany)); ++i) {
    if (topic == kOneToMany[i]) {
      return options::kRtpsPortBase + options::kRtpsDomainGain * domain_id + kFirstFreeOffset + i;
    }
  }
  return std::nullopt;
}

namespace {

template <typename EndpointQos>
void apply_common(EndpointQos& qos, const std::string& topic, bool best_effort_data) {
  qos.reliability().kind = best_effort_data && is_data_link_topic(topic)
                               ? dds::BEST_EFFORT_RELIABILITY_QOS
                               : dds::RELIABLE_RELIABILITY_QOS;
  qos.durability().kind =
      is_keyed_topic(topic) ? dds::TRANSIENT_LOCAL_DURABILITY_QOS : dds::VOLATILE_DURABILITY_QOS;
  qos.history().kind = dds::KEEP_ALL_HISTORY_QOS;
  // Fast DDS refuses limits where max_samples < max_instances * max_samples_per_instance.
  if (is_keyed_topic(topic)) {
    qos.resource_limits().max_instances = kMaxInstances;
    qos.resource_limits().max_samples_per_instance = kSamplesPerInstance;
    qos.resource_limits().max_samples = kMaxInstances * kSamplesPerInstance;
  } else {
    qos.resource_limits().max_instances = 1;
    qos.resource_limits().max_samples = kMaxSamples;
    qos.resource_limits().max_samples_per_instance = kMaxSamples;
  }
  qos.resource_limits().allocated_samples = 64;
  if (is_latest_state_topic(topic)) {
    qos.durability().kind = dds::TRANSIENT_LOCAL_DURABILITY_QOS;
    qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    qos.history().depth = 1;
  }
  // Data-sharing would put samples in /dev/shm segments that a killed process leaves behind;
  // at ~500 bytes a sample the copy is not what costs (wake-ups are).
  qos.data_sharing().off();
}

}  // namespace

QosProfiles::QosProfiles(const std::optional<std::filesystem::path>& xml_file,
                         bool best_effort_data, int domain_id, options::NetworkOptions network,
                         bool serves_discovery)
    : best_effort_data_(best_effort_data),
      domain_id_(domain_id),
      network_(std::move(network)),
      serves_discovery_(serves_discovery) {
  if (serves_discovery_ && !network_.discovery_server) {
    throw std::invalid_argument("a discovery server needs its address");
  }
  auto* factory = dds::DomainParticipantFactory::get_instance();
  if (xml_file && factory->load_XML_profiles_file(xml_file->string()) != ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error(
        fmt::format("--qos: cannot load Fast DDS XML profiles from {}", xml_file->string()));
  }
  dds::DomainParticipantQos user_profile;
  if (factory->get_participant_qos_from_profile("skyfuse_participant", user_profile) ==
      ReturnCode_t::RETCODE_OK) {
    user_participant_ = user_profile;
  }
}

dds::DomainParticipantQos QosProfiles::participant(const std::string& name) const {
  dds::DomainParticipantQos qos = user_participant_.value_or(dds::DomainParticipantQos());
  qos.name(name);
  if (user_participant_) return qos;
  // UDP on one interface only - loopback by default: one host, no traffic leaves it - and no
  // shared-memory segments for a killed process to leave in /dev/shm, nor for two simulated
  // hosts (network namespaces) to share. Runs across hosts give each node its host's address.
  qos.transport().use_builtin_transports = false;
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->interfaceWhiteList.emplace_back(network_.interface_address);
  // With the default 208 KiB, a round's burst overflowed the sockets from ~20 stations on and
  // each lost datagram waited for a repair: M = 32, 300 rounds: 33 810 datagrams dropped,
  // 14 rounds/s; with 4 MiB none, 19 rounds/s. The kernel caps it at net.core.rmem_max.
  udp->receiveBufferSize = static_cast<std::uint32_t>(kReceiveBufferBytes);
  qos.transport().user_transports.push_back(udp);
  // A dead participant is noticed after its lease: 10 s instead of the default 20 s, longer for
  // large runs (options::lease_seconds). Shorter leases (2 s was tried) expire on a starved machine
  // - 30+ processes on 2 cores - and Debian's Fast DDS, built with assertions, then aborts in
  // PDP::check_remote_participant_liveliness. The harness does not rely on leases: it sees a dead
  // child through waitpid at once.
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.leaseDuration = Duration_t(static_cast<long double>(network_.lease_s));
  // Every participant announces itself to every other one each period: M^2 datagrams. At
  // M = 64 and 1 s that was 4 300 receptions a second, a sixth of a tree round's; at 3 s (Fast
  // DDS's default) a third of that. Lock-step M = 64, tree exchange, best effort: 69 -> 68-85
  // rounds/s (several runs; the spread between runs is as large as the gain).
  discovery.leaseDuration_announcementperiod = Duration_t(3, 0);
  // Announce quickly at start so that all-matched is reached in tenths of a second.
  discovery.initial_announcements.count = 10;
  discovery.initial_announcements.period = Duration_t(0, 50'000'000);
  // Fast DDS sizes its pool of send buffers by the threads it knows to send from, and a send
  // waits for a free buffer. Stations sharing a participant (`skyfuse-station --id A --id B`)
  // send from threads of their own, and a send can wait while holding a reader's lock for an
  // in-process delivery that another sender holding a buffer waits on: with 16 stations in a
  // process, a group hung in discovery, every sender in SendBuffersManager::get_buffer or
  // StatefulReader::processDataMsg. Growing the pool instead of waiting costs an allocation
  // only when it is empty.
  qos.allocation().send_buffers.dynamic = true;
  if (network_.participant_id) qos.wire_protocol().participant_id = *network_.participant_id;
  if (network_.discovery_server) use_discovery_server(qos, *network_.discovery_server);
  if (!network_.discovery_peers.empty()) announce_to_peers_only(qos);
  return qos;
}

void QosProfiles::announce_to_peers_only(dds::DomainParticipantQos& qos) const {
  // Simple discovery, but announced by unicast to the listed peers only. A participant learns
  // of another only from that one's announcement, and announces itself to its initial peers
  // and to those it has learnt of (by unicast: Fast DDS avoids multicast for built-in traffic
  // after discovery). So it knows the peers it lists and those that list or reach it.
  // It still listens on the domain's discovery multicast group, which none of the run's
  // processes send to, so that a reader of another DDS that announces itself by multicast (a
  // viewer, docs/interop.md) is answered and finds it as before. Fast DDS adds the default
  // locators only when both lists are empty; port 0 becomes the well-known port.
  namespace rtps = eprosima::fastrtps::rtps;
  auto& builtin = qos.wire_protocol().builtin;
  rtps::Locator_t own;
  rtps::IPLocator::createLocator(LOCATOR_KIND_UDPv4, network_.interface_address, 0, own);
  builtin.metatrafficUnicastLocatorList.push_back(own);
  rtps::Locator_t group;
  rtps::IPLocator::createLocator(LOCATOR_KIND_UDPv4, kMulticastGroup, 0, group);
  builtin.metatrafficMulticastLocatorList.push_back(group);
  for (const options::Ipv4Endpoint& peer : network_.discovery_peers) {
    rtps::Locator_t locator;
    rtps::IPLocator::createLocator(LOCATOR_KIND_UDPv4, peer.address, peer.port, locator);
    builtin.initialPeersList.push_back(locator);
  }
}

dds::DataWriterQos QosProfiles::writer(const dds::Publisher& publisher,
                                       const std::string& profile) const {
  dds::DataWriterQos qos = dds::DATAWRITER_QOS_DEFAULT;
  if (publisher.get_datawriter_qos_from_profile(profile + "_writer", qos) ==
      ReturnCode_t::RETCODE_OK) {
    return qos;
  }
  apply_common(qos, profile, best_effort_data_);
  if (is_status_topic(profile)) {
    qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    qos.history().depth = 1;
  } else if (is_track_topic(profile)) {
    qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    qos.history().depth = kSamplesPerInstance;
  } else if (is_picture_track_profile(profile)) {
    qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    qos.history().depth = 1;
    qos.resource_limits().max_instances = kMaxPictureTracks;
    qos.resource_limits().max_samples_per_instance = 1;
    qos.resource_limits().max_samples = kMaxPictureTracks;
  }
  qos.reliability().max_blocking_time = kMaxBlockingTime;
  qos.reliable_writer_qos().times.heartbeatPeriod = kHeartbeatPeriod;
  qos.reliable_writer_qos().times.nackResponseDelay = Duration_t(0, 0);
  qos.reliable_writer_qos().times.nackSupressionDuration = kNackSuppression;
  qos.publish_mode().kind = dds::SYNCHRONOUS_PUBLISH_MODE;
  return qos;
}

dds::DataReaderQos QosProfiles::reader(const dds::Subscriber& subscriber,
                                       const std::string& topic) const {
  dds::DataReaderQos qos = dds::DATAREADER_QOS_DEFAULT;
  if (subscriber.get_datareader_qos_from_profile(topic + "_reader", qos) ==
      ReturnCode_t::RETCODE_OK) {
    return qos;
  }
  apply_common(qos, topic, best_effort_data_);
  qos.reliable_reader_qos().times.heartbeatResponseDelay = Duration_t(0, 0);
  // One datagram per write for all readers instead of one per reader: a station's increment
  // is 1 send instead of M - 1. `skyfuse run --steps 3000`, three runs each way: M = 8 used
  // 4.46 -> 3.72 ms of CPU per round (all processes) and ran 433 -> 524 rounds/s; M = 4 is
  // unchanged within the noise (1.68 -> 1.64 ms). The reader keeps its unicast locators for
  // repairs. Multicast leaves the host only if the participant's interfaces do, and the
  // built-in participant's is 127.0.0.1.
  if (const auto port = multicast_port(topic, domain_id_); port && multicast()) {
    eprosima::fastrtps::rtps::Locator_t group;
    eprosima::fastrtps::rtps::IPLocator::createLocator(LOCATOR_KIND_UDPv4, kMulticastGroup,
                                                       static_cast<std::uint32_t>(*port), group);
    qos.endpoint().multicast_locator_list.push_back(group);
  }
  return qos;
}

void QosProfiles::use_discovery_server(dds::DomainParticipantQos& qos,
                                       const options::Ipv4Endpoint& server) const {
  // Clients must know their server's GUID prefix (Fast DDS 2.9): server id 0's, the one the
  // headers give `fastdds discovery -i 0`.
  namespace rtps = eprosima::fastrtps::rtps;
  rtps::Locator_t locator;
  rtps::IPLocator::createLocator(LOCATOR_KIND_UDPv4, server.address, server.port, locator);
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  if (serves_discovery_) {
    discovery.discoveryProtocol = rtps::DiscoveryProtocol_t::SERVER;
    std::istringstream(eprosima::fastdds::rtps::DEFAULT_ROS2_SERVER_GUIDPREFIX) >>
        qos.wire_protocol().prefix;
    qos.wire_protocol().builtin.metatrafficUnicastLocatorList.push_back(locator);
    return;
  }
  discovery.discoveryProtocol = rtps::DiscoveryProtocol_t::CLIENT;
  eprosima::fastdds::rtps::RemoteServerAttributes remote;
  remote.ReadguidPrefix(eprosima::fastdds::rtps::DEFAULT_ROS2_SERVER_GUIDPREFIX);
  remote.metatrafficUnicastLocatorList.push_back(locator);
  discovery.m_DiscoveryServers.push_back(remote);
}

}  // namespace skyfuse::transport
