#include "cover/dds/participant_options.hpp"

#include <arpa/inet.h>

#include <cstdlib>

#include "cover/config/yaml_reader.hpp"
#include "cover/dds/dds_error.hpp"

namespace cover::dds {

void ParticipantOptions::validate() const {
  if (domain_id < 0 || domain_id > kMaxDomainId) {
    throw DdsError("invalid DDS domain id " + std::to_string(domain_id) + " (valid: 0.." +
                   std::to_string(kMaxDomainId) + ")");
  }
  for (const auto& peer : peers) {
    in_addr address{};
    if (inet_pton(AF_INET, peer.c_str(), &address) != 1) {
      throw DdsError("invalid DDS peer address '" + peer + "' (expected IPv4, e.g. 10.0.0.2)");
    }
  }
}

ParticipantOptions ParticipantOptions::load_file(const std::string& path) {
  ParticipantOptions options;
  config::YamlReader dds = config::open_section(path, "dds", /*required=*/false);
  std::string vendor = vendor_name(options.vendor);
  dds.optional("vendor", vendor);
  dds.optional("domain_id", options.domain_id);
  dds.optional("interface", options.interface_name);
  dds.optional("peers", options.peers);
  dds.optional("fastdds_shared_memory", options.fastdds_shared_memory);
  dds.reject_unknown_keys();
  try {
    options.vendor = parse_vendor(vendor);
    options.validate();
  } catch (const DdsError& e) {
    throw config::ConfigError(path + ": " + e.what());
  }
  return options;
}

ParticipantOptions apply_environment(ParticipantOptions options) {
  options.vendor = vendor_from_environment(options.vendor);
  if (const char* domain = std::getenv("COVER_DDS_DOMAIN"); domain && *domain) {
    char* end = nullptr;
    const long value = std::strtol(domain, &end, 10);
    if (*end != '\0') throw DdsError(std::string("COVER_DDS_DOMAIN is not a number: ") + domain);
    options.domain_id = static_cast<int>(value);
  }
  return options;
}

}  // namespace cover::dds
