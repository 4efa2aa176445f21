#include "skyfuse/transport/dds_node.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include "skyfuse/transport/port_probe.hpp"

namespace skyfuse::transport {

bool ReaderWaitSet::wait(std::chrono::microseconds timeout) {
  dds::ConditionSeq active;
  return wait_set_.wait(active, to_dds_duration(timeout)) == ReturnCode_t::RETCODE_OK;
}

DdsNode::DdsNode(const NodeConfig& config)
    : qos_(config.qos_file, config.best_effort_data, config.domain_id, config.network,
           config.serves_discovery) {
  if (config.domain_id < 0 || config.domain_id > kMaxDomainId) {
    throw DdsError(
        fmt::format("--domain: must be in [0, {}], got {}", kMaxDomainId, config.domain_id));
  }
  // Fast DDS opens a multicast port another socket holds without a word, and its samples are
  // then lost (port_probe.hpp): say so before anything is created.
  if (qos_.multicast()) {
    if (const auto taken = taken_multicast_port(config.domain_id)) throw DdsError(*taken);
  }
  auto* factory = dds::DomainParticipantFactory::get_instance();
  dds::DomainParticipantQos participant_qos = qos_.participant(config.name);
  if (config.security) add_security_properties(participant_qos, *config.security);
  // No status in the mask: the listener hears discovery only, and the readers' events stay
  // with their WaitSets.
  participant_ = factory->create_participant(config.domain_id, participant_qos, discovery_.get(),
                                             dds::StatusMask::none());
  if (participant_ == nullptr) {
    throw DdsError(fmt::format("cannot create a DDS participant on domain {}{}", config.domain_id,
                               config.security ? " with DDS-Security (see the log above)" : ""));
  }
  publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  if (publisher_ == nullptr || subscriber_ == nullptr) {
    participant_->delete_contained_entities();
    factory->delete_participant(participant_);
    throw DdsError("cannot create the DDS publisher or subscriber");
  }
}

dds::Publisher* DdsNode::publisher_in(const std::vector<std::string>& partitions) {
  dds::PublisherQos qos = dds::PUBLISHER_QOS_DEFAULT;
  for (const std::string& name : partitions) qos.partition().push_back(name.c_str());
  dds::Publisher* publisher = participant_->create_publisher(qos);
  if (publisher == nullptr)
    throw DdsError("cannot create a publisher in partition " + partitions[0]);
  return publisher;
}

dds::Subscriber* DdsNode::subscriber_in(const std::vector<std::string>& partitions) {
  dds::SubscriberQos qos = dds::SUBSCRIBER_QOS_DEFAULT;
  for (const std::string& name : partitions) qos.partition().push_back(name.c_str());
  dds::Subscriber* subscriber = participant_->create_subscriber(qos);
  if (subscriber == nullptr) {
    throw DdsError("cannot create a subscriber in partition " + partitions[0]);
  }
  return subscriber;
}

void DdsNode::DiscoveryCount::on_participant_discovery(
    dds::DomainParticipant*, eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) {
  using Status = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo::DISCOVERY_STATUS;
  switch (info.status) {
    case Status::DISCOVERED_PARTICIPANT:
      ++known_;
      break;
    case Status::REMOVED_PARTICIPANT:
    case Status::DROPPED_PARTICIPANT:
      if (known_ > 0) --known_;
      // Dropped: its lease ran out, which on a starved machine may be a live participant.
      spdlog::info("participant {} {}", info.info.m_participantName.to_string(),
                   info.status == Status::DROPPED_PARTICIPANT ? "dropped (lease expired)" : "left");
      break;
    default:
      break;
  }
}

DdsNode::~DdsNode() {
  if (participant_ == nullptr) return;
  participant_->delete_contained_entities();
  dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

}  // namespace skyfuse::transport
