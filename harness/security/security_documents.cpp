#include "security/security_documents.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <ctime>

#include "skyfuse/transport/node_config.hpp"
#include "skyfuse/transport/picture_bundles.hpp"
#include "skyfuse/transport/refusal_reports.hpp"
#include "skyfuse/transport/topics.hpp"
#include "skyfuse/transport/tree_partitions.hpp"

namespace skyfuse::harness {
namespace {

constexpr const char* kOrganisation = "skyfuse";
constexpr const char* kHeader = R"(<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance")";

// Every domain id a skyfuse process accepts, so that one folder serves any --domain.
std::string all_domains(const std::string& indent) {
  return fmt::format(
      "{0}<domains>\n{0}  <id_range><min>0</min><max>{1}</max></id_range>\n{0}</domains>\n", indent,
      transport::kMaxDomainId);
}

std::string topic_rule(const std::string& topic) {
  return fmt::format(R"(        <topic_rule>
          <topic_expression>{}</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
)",
                     topic);
}

// A <publish> or <subscribe> criterion: its topics, in `partitions` if any are given (else the
// default partition).
std::string topic_list(const char* element, const std::vector<std::string>& topics,
                       const std::vector<std::string>& partitions = {}) {
  if (topics.empty()) return {};
  std::string text = fmt::format("        <{}>\n          <topics>\n", element);
  for (const std::string& t : topics) text += fmt::format("            <topic>{}</topic>\n", t);
  text += "          </topics>\n";
  if (!partitions.empty()) {
    text += "          <partitions>\n";
    for (const std::string& p : partitions) {
      text += fmt::format("            <partition>{}</partition>\n", p);
    }
    text += "          </partitions>\n";
  }
  return text + fmt::format("        </{}>\n", element);
}

// The partitions of a picture's tree exchange (transport/picture_bundles.hpp).
std::vector<std::string> picture_tree_partitions() {
  return {transport::kPictureClustersPartition, transport::kEveryClusterUpPattern};
}

// The validity format of the permissions schema: UTC, no zone suffix.
std::string xml_time(std::chrono::system_clock::time_point t) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(t);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  return fmt::format("{:%Y-%m-%dT%H:%M:%S}", utc);
}

}  // namespace

std::vector<std::string> skyfuse_topics() {
  using transport::TopicTraits;
  return {TopicTraits<wire::Tick>::kName,
          TopicTraits<wire::Measurement>::kName,
          TopicTraits<wire::InformationIncrement>::kName,
          TopicTraits<wire::PartialSum>::kName,
          TopicTraits<wire::TrackEstimate>::kName,
          TopicTraits<wire::StationStatus>::kName,
          TopicTraits<wire::PictureScan>::kName,
          TopicTraits<wire::PictureBundle>::kName,
          TopicTraits<wire::PictureRound>::kName,
          TopicTraits<wire::PictureState>::kName};
}

std::string governance_xml(const std::vector<std::string>& topics) {
  std::string rules;
  for (const std::string& t : topics) rules += topic_rule(t);
  return fmt::format(R"({}
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
{}      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>ENCRYPT</rtps_protection_kind>
      <topic_access_rules>
{}      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
)",
                     kHeader, all_domains("      "), rules);
}

std::string subject_name(const std::string& identity) {
  return fmt::format("CN={},O={}", identity, kOrganisation);
}

std::string openssl_subject(const std::string& identity) {
  return fmt::format("/O={}/CN={}", kOrganisation, identity);
}

std::string permissions_xml(const std::vector<AccessGrant>& grants,
                            std::chrono::system_clock::time_point not_before,
                            std::chrono::system_clock::time_point not_after) {
  std::string text = fmt::format(R"({}
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
)",
                                 kHeader);
  for (const AccessGrant& g : grants) {
    text += fmt::format(
        R"(    <grant name="{0}">
      <subject_name>{1}</subject_name>
      <validity>
        <not_before>{2}</not_before>
        <not_after>{3}</not_after>
      </validity>
      <allow_rule>
{4}{5}{6}{7}{8}{9}{10}      </allow_rule>
      <default>DENY</default>
    </grant>
)",
        g.identity, subject_name(g.identity), xml_time(not_before), xml_time(not_after),
        all_domains("        "), topic_list("publish", g.publish),
        topic_list("subscribe", g.subscribe),
        topic_list("publish", g.publish_refusal_reports, {transport::kRefusalReportsPartition}),
        topic_list("subscribe", g.subscribe_refusal_reports, {transport::kRefusalReportsPartition}),
        topic_list("publish", g.publish_in_picture_tree, picture_tree_partitions()),
        topic_list("subscribe", g.subscribe_in_picture_tree, picture_tree_partitions()));
  }
  return text + "  </permissions>\n</dds>\n";
}

}  // namespace skyfuse::harness
