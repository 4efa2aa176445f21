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

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <filesystem>
#include <optional>
#include <string>

namespace eprosima::fastdds::dds {
class Publisher;
class Subscriber;
}  // namespace eprosima::fastdds::dds

namespace skyfuse::transport {

/// Largest station count the resource limits are sized for (the wire types allow as many).
inline constexpr int kMaxStations = 256;

class QosProfiles {
 public:
  /// Loads `xml_file` if given; a file that does not load is an error, not a silent default.
  /// `best_effort_data`: the data links (increments, measurements) are BEST_EFFORT.
  QosProfiles(const std::optional<std::filesystem::path>& xml_file, bool best_effort_data);

  eprosima::fastdds::dds::DomainParticipantQos participant(const std::string& name) const;
  eprosima::fastdds::dds::DataWriterQos writer(const eprosima::fastdds::dds::Publisher& publisher,
                                               const std::string& topic) const;
  eprosima::fastdds::dds::DataReaderQos reader(const eprosima::fastdds::dds::Subscriber& subscriber,
                                               const std::string& topic) const;

 private:
  bool best_effort_data_;
};

}  // namespace skyfuse::transport
