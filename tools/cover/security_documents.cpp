#include "security_documents.hpp"

#include <string_view>
#include <vector>

namespace cover::cli {
namespace {

constexpr const char* kSchema = "http://www.omg.org/spec/DDS-SECURITY/20170901/";

std::string header(const std::string& xsd) {
  return std::string(
             "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
             "xsi:noNamespaceSchemaLocation=\"") +
         kSchema + xsd + "\">\n";
}

std::string domains(int max_domain, const std::string& indent) {
  return indent + "<domains><id_range><min>0</min><max>" + std::to_string(max_domain) +
         "</max></id_range></domains>\n";
}

std::string topic_list(std::string_view tag, const std::vector<std::string>& topics) {
  if (topics.empty()) return "";
  std::string xml = "        <" + std::string(tag) + ">\n          <topics>\n";
  for (const auto& topic : topics) xml += "            <topic>" + topic + "</topic>\n";
  return xml + "          </topics>\n        </" + std::string(tag) + ">\n";
}

}  // namespace

std::string governance_xml(int max_domain) {
  return header("omg_shared_ca_governance.xsd") +
         "  <domain_access_rules>\n"
         "    <domain_rule>\n" +
         domains(max_domain, "      ") +
         "      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>\n"
         "      <enable_join_access_control>true</enable_join_access_control>\n"
         "      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>\n"
         "      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>\n"
         "      <rtps_protection_kind>NONE</rtps_protection_kind>\n"
         "      <topic_access_rules>\n"
         "        <topic_rule>\n"
         "          <topic_expression>*</topic_expression>\n"
         "          <enable_discovery_protection>true</enable_discovery_protection>\n"
         "          <enable_liveliness_protection>true</enable_liveliness_protection>\n"
         "          <enable_read_access_control>true</enable_read_access_control>\n"
         "          <enable_write_access_control>true</enable_write_access_control>\n"
         "          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>\n"
         "          <data_protection_kind>ENCRYPT</data_protection_kind>\n"
         "        </topic_rule>\n"
         "      </topic_access_rules>\n"
         "    </domain_rule>\n"
         "  </domain_access_rules>\n"
         "</dds>\n";
}

std::string permissions_xml(const std::string& grant_name, const std::string& subject,
                            const std::string& not_before_utc, const std::string& not_after_utc,
                            const dds::TopicAccess& access, int max_domain) {
  return header("omg_shared_ca_permissions.xsd") +
         "  <permissions>\n"
         "    <grant name=\"" +
         grant_name +
         "\">\n"
         "      <subject_name>" +
         subject +
         "</subject_name>\n"
         "      <validity>\n"
         "        <not_before>" +
         not_before_utc +
         "</not_before>\n"
         "        <not_after>" +
         not_after_utc +
         "</not_after>\n"
         "      </validity>\n"
         "      <allow_rule>\n" +
         domains(max_domain, "        ") + topic_list("publish", access.publish) +
         topic_list("subscribe", access.subscribe) +
         "      </allow_rule>\n"
         "      <default>DENY</default>\n"
         "    </grant>\n"
         "  </permissions>\n"
         "</dds>\n";
}

}  // namespace cover::cli
