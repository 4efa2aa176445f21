#pragma once
/// \file
/// One DDS participant per process, with its publisher, subscriber and topics, and typed
/// endpoints on top. Entities are created in a fixed order and deleted with the node. Every
/// write is checked; every endpoint reports how many remote endpoints it has matched.
///
/// Threading: an endpoint belongs to the thread that created it; readers are waited on with a
/// WaitSet on that thread (no listener does work). Endpoints may be made from several threads
/// (the stations that share a process's participant, `skyfuse-station --id A --id B`).

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <fastdds/dds/core/condition/WaitSet.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "skyfuse/transport/node_config.hpp"
#include "skyfuse/transport/qos.hpp"
#include "skyfuse/transport/security.hpp"
#include "skyfuse/transport/topics.hpp"

namespace skyfuse::transport {

namespace dds = eprosima::fastdds::dds;

inline std::array<std::uint8_t, 16> to_writer_id(const dds::InstanceHandle_t& handle) {
  std::array<std::uint8_t, 16> id{};
  for (std::size_t i = 0; i < id.size(); ++i) id[i] = handle.value[i];
  return id;
}

/// A std::chrono duration as a DDS Duration_t.
inline eprosima::fastrtps::Duration_t to_dds_duration(std::chrono::microseconds d) {
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(d);
  const auto nanos = std::chrono::duration_cast<std::chrono::nanoseconds>(d - seconds);
  return {static_cast<int32_t>(seconds.count()), static_cast<uint32_t>(nanos.count())};
}

/// Moves a publisher or a subscriber, and with it its endpoints, to other DDS partitions.
template <typename Group>
void move_group(Group* group, const std::vector<std::string>& partitions, const char* what) {
  auto qos = group->get_qos();
  qos.partition().clear();
  for (const std::string& name : partitions) qos.partition().push_back(name.c_str());
  if (group->set_qos(qos) != ReturnCode_t::RETCODE_OK) {
    throw DdsError(std::string("cannot move a ") + what + " to partition " + partitions.front());
  }
}

template <typename T>
class Writer {
 public:
  explicit Writer(dds::DataWriter* writer) : writer_(writer) {}
  /// Throws DdsError when the sample could not be queued (reliable history full for longer
  /// than max_blocking_time): a lost sample is never silent.
  void write(const T& sample) {
    if (!writer_->write(const_cast<T*>(&sample))) {
      throw DdsError(std::string("write failed on topic ") + TopicTraits<T>::kName);
    }
  }
  /// Ends the instance of `sample`'s key (a keyed topic): readers see it disposed, since Fast
  /// DDS disposes an instance its writer unregisters (autodispose_unregistered_instances), and
  /// the writer may reuse its place. Throws DdsError if Fast DDS refuses.
  void unregister(const T& sample) {
    if (writer_->unregister_instance(const_cast<T*>(&sample), dds::HANDLE_NIL) !=
        ReturnCode_t::RETCODE_OK) {
      throw DdsError(std::string("unregister failed on topic ") + TopicTraits<T>::kName);
    }
  }
  /// Waits until every matched reader acknowledged every sample: call before exiting, or the
  /// last samples may die with the participant.
  bool wait_acknowledged(std::chrono::microseconds timeout) {
    return writer_->wait_for_acknowledgments(to_dds_duration(timeout)) == ReturnCode_t::RETCODE_OK;
  }
  /// What a reader's take() reports as this writer's id.
  WriterId id() const { return to_writer_id(writer_->get_instance_handle()); }
  /// Moves the writer to other DDS partitions (one made with partitions has a publisher of its
  /// own): it leaves the readers it matched there and matches those of the new ones, as
  /// discovery tells the others. Throws DdsError if Fast DDS refuses.
  void set_partitions(const std::vector<std::string>& partitions) {
    // Fast DDS 2.9 hands out only a const pointer to an endpoint's publisher.
    move_group(const_cast<dds::Publisher*>(writer_->get_publisher()), partitions, "writer");
  }
  /// Remote readers currently matched (this participant's own matching reader included).
  int matched() const {
    dds::PublicationMatchedStatus status;
    writer_->get_publication_matched_status(status);
    return status.current_count;
  }

 private:
  dds::DataWriter* writer_;
};

template <typename T>
class Reader {
 public:
  explicit Reader(dds::DataReader* reader) : reader_(reader) {
    reader_->get_statuscondition().set_enabled_statuses(dds::StatusMask::data_available());
  }
  /// Takes the next valid sample; false when none is left. `writer`, if given, receives the
  /// id of the writer that sent it.
  bool take(T& sample, WriterId* writer = nullptr) {
    dds::SampleInfo info;
    while (reader_->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      if (writer != nullptr) *writer = to_writer_id(info.publication_handle);
      return true;
    }
    return false;
  }
  int matched() const {
    dds::SubscriptionMatchedStatus status;
    reader_->get_subscription_matched_status(status);
    return status.current_count;
  }
  dds::StatusCondition& condition() { return reader_->get_statuscondition(); }
  /// Moves the reader to other DDS partitions, as Writer::set_partitions.
  void set_partitions(const std::vector<std::string>& partitions) {
    move_group(const_cast<dds::Subscriber*>(reader_->get_subscriber()), partitions, "reader");
  }

 private:
  dds::DataReader* reader_;
};

/// Sleeps until any attached reader has data or the timeout passes.
class ReaderWaitSet {
 public:
  template <typename T>
  void attach(Reader<T>& reader) {
    wait_set_.attach_condition(reader.condition());
  }
  /// True if woken by data, false on timeout.
  bool wait(std::chrono::microseconds timeout);

 private:
  dds::WaitSet wait_set_;
};

class DdsNode {
 public:
  explicit DdsNode(const NodeConfig& config);
  ~DdsNode();
  DdsNode(const DdsNode&) = delete;
  DdsNode& operator=(const DdsNode&) = delete;

  /// A writer of T's topic. With `partitions` (DDS partition names), its own publisher in them:
  /// it matches only readers in one of them, and the others never receive its samples (the
  /// tree exchange's clusters). Without, the node's publisher, in the default partition.
  /// `profile` names its QoS (QosProfiles::writer): the topic's own unless the writer keeps
  /// its samples otherwise (a picture's tracks: kPictureTrackProfile).
  template <typename T>
  Writer<T> make_writer(const std::vector<std::string>& partitions = {},
                        const std::string& profile = TopicTraits<T>::kName) {
    const std::lock_guard lock(entities_);
    dds::Topic* topic = topic_for<T>();
    dds::Publisher* publisher = partitions.empty() ? publisher_ : publisher_in(partitions);
    dds::DataWriter* writer = publisher->create_datawriter(topic, qos_.writer(*publisher, profile));
    if (writer == nullptr)
      throw DdsError(std::string("cannot create writer for ") + topic->get_name());
    return Writer<T>(writer);
  }

  /// Other participants this one has discovered and not lost since: every process of the
  /// domain with multicast discovery, only the peers with `--discovery-peers`.
  std::size_t participants_known() const { return discovery_->known(); }

  /// A reader of T's topic; with `partitions`, its own subscriber in them (as make_writer).
  template <typename T>
  Reader<T> make_reader(const std::vector<std::string>& partitions = {}) {
    const std::lock_guard lock(entities_);
    dds::Topic* topic = topic_for<T>();
    dds::Subscriber* subscriber = partitions.empty() ? subscriber_ : subscriber_in(partitions);
    dds::DataReader* reader =
        subscriber->create_datareader(topic, qos_.reader(*subscriber, TopicTraits<T>::kName));
    if (reader == nullptr)
      throw DdsError(std::string("cannot create reader for ") + topic->get_name());
    return Reader<T>(reader);
  }

 private:
  template <typename T>
  dds::Topic* topic_for() {
    const std::string name = TopicTraits<T>::kName;
    if (auto it = topics_.find(name); it != topics_.end()) return it->second;
    dds::TypeSupport type(new typename TopicTraits<T>::PubSubType());
    if (type.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
      throw DdsError("cannot register type for " + name);
    }
    dds::Topic* topic =
        participant_->create_topic(name, type.get_type_name(), dds::TOPIC_QOS_DEFAULT);
    if (topic == nullptr) throw DdsError("cannot create topic " + name);
    topics_.emplace(name, topic);
    return topic;
  }

  // A publisher / subscriber of its own in `partitions`, deleted with the participant.
  dds::Publisher* publisher_in(const std::vector<std::string>& partitions);
  dds::Subscriber* subscriber_in(const std::vector<std::string>& partitions);

  // Counts the participants discovered and lost, on Fast DDS's discovery thread.
  class DiscoveryCount : public dds::DomainParticipantListener {
   public:
    std::size_t known() const { return known_.load(); }
    void on_participant_discovery(
        dds::DomainParticipant*,
        eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;

   private:
    std::atomic<std::size_t> known_{0};
  };

  QosProfiles qos_;
  std::unique_ptr<DiscoveryCount> discovery_ = std::make_unique<DiscoveryCount>();
  dds::DomainParticipant* participant_ = nullptr;
  dds::Publisher* publisher_ = nullptr;
  dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, dds::Topic*> topics_;
  // Held while endpoints are made: the topics and the partitions' groups are made on first use.
  std::mutex entities_;
};

}  // namespace skyfuse::transport
