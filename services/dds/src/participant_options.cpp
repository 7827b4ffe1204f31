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
  if (!(announcement_period_s >= 0.0 && announcement_period_s <= 3600.0)) {
    throw DdsError("invalid announcement_period_s " + std::to_string(announcement_period_s) +
                   " (valid: 0 = vendor default, or up to 3600 s)");
  }
  if (participants_per_peer < 1 || participants_per_peer > kMaxParticipantsPerPeer) {
    throw DdsError("invalid participants_per_peer " + std::to_string(participants_per_peer) +
                   " (valid: 1.." + std::to_string(kMaxParticipantsPerPeer) + ")");
  }
  if (security.expiry_warning_days < 0 || security.expiry_warning_days > kMaxValidityDays) {
    throw DdsError("invalid security.expiry_warning_days " +
                   std::to_string(security.expiry_warning_days) + " (valid: 0.." +
                   std::to_string(kMaxValidityDays) + " days)");
  }
  if (!discovery_server.empty()) parse_server_address(discovery_server);
  // Not security.validate(): a file or profile may leave the identity to --identity;
  // check_participant_security checks the complete options before a participant exists.
  for (const auto& peer : peers) {
    in_addr address{};
    if (inet_pton(AF_INET, peer.c_str(), &address) != 1) {
      throw DdsError("invalid DDS peer address '" + peer + "' (expected IPv4, e.g. 10.0.0.2)");
    }
  }
}

ServerAddress parse_server_address(const std::string& text) {
  const auto colon = text.rfind(':');
  const auto bad = [&] {
    return DdsError("invalid discovery_server '" + text + "' (expected IPv4:port, e.g. " +
                    "127.0.0.1:11811)");
  };
  if (colon == std::string::npos) throw bad();
  ServerAddress server{text.substr(0, colon), 0};
  const std::string port = text.substr(colon + 1);
  in_addr address{};
  if (inet_pton(AF_INET, server.address.c_str(), &address) != 1 || port.empty() ||
      port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos) {
    throw bad();
  }
  server.port = std::stoi(port);
  if (server.port < 1 || server.port > 65535) throw bad();
  return server;
}

namespace {

// The network and security keys, which the top level and every profile share.
void read_network_keys(config::YamlReader& reader, ParticipantOptions& options) {
  reader.optional("interface", options.interface_name);
  reader.optional("peers", options.peers);
  reader.optional("discovery_server", options.discovery_server);
  reader.optional("fastdds_shared_memory", options.fastdds_shared_memory);
  reader.optional("announcement_period_s", options.announcement_period_s);
  reader.optional("participants_per_peer", options.participants_per_peer);
  config::YamlReader security = reader.child("security");
  security.optional("enabled", options.security.enabled);
  security.optional("directory", options.security.directory);
  security.optional("identity", options.security.identity);
  security.optional("expiry_warning_days", options.security.expiry_warning_days);
  security.reject_unknown_keys();
}

// Applies profile `name` of `profiles` on top of `options`; every profile is checked (keys and
// values), so that a typo in one not selected today still fails loudly.
void apply_profile(config::YamlReader profiles, const std::string& name,
                   ParticipantOptions& options) {
  bool found = name.empty();
  std::string known;
  if (profiles.node().IsMap()) {
    for (const auto& entry : profiles.node()) {
      // A list or a mapping as a profile's name (`? wifi:`, a stray `?`) names nothing.
      config::check(entry.first.IsScalar(), profiles.context(),
                    "a profile name that is not a name" + config::line_of(entry.first));
      const auto key = entry.first.Scalar();
      known += (known.empty() ? "" : ", ") + key;
      ParticipantOptions scratch;
      config::YamlReader profile = profiles.child(key);
      read_network_keys(profile, key == name ? options : scratch);
      profile.reject_unknown_keys();
      // A profile not selected today is still checked: it is what the field will run.
      try {
        scratch.validate();
      } catch (const DdsError& e) {
        throw config::ConfigError(profile.context() + ": " + e.what());
      }
      found = found || key == name;
    }
  }
  if (!found) {
    throw config::ConfigError(profiles.context() + ": no DDS profile '" + name +
                              "' (known: " + (known.empty() ? "none" : known) + ")");
  }
  profiles.reject_unknown_keys();
}

}  // namespace

ParticipantOptions ParticipantOptions::load_file(const std::string& path,
                                                 const std::string& profile) {
  return from_yaml(config::load_yaml_file(path), path, profile);
}

ParticipantOptions ParticipantOptions::from_yaml(const YAML::Node& document,
                                                 const std::string& source,
                                                 const std::string& profile) {
  ParticipantOptions options;
  config::YamlReader dds = config::open_section(document, source, "dds", /*required=*/false);
  std::string vendor = vendor_name(options.vendor);
  dds.optional("vendor", vendor);
  dds.optional("domain_id", options.domain_id);
  read_network_keys(dds, options);
  apply_profile(dds.child("profiles"), profile, options);
  dds.reject_unknown_keys();
  try {
    options.vendor = parse_vendor(vendor);
    options.validate();
  } catch (const DdsError& e) {
    throw config::ConfigError(source + ": " + e.what());
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
  if (const char* directory = std::getenv(kSecurityEnvironment); directory && *directory) {
    options.security.enabled = true;
    options.security.directory = directory;
  }
  // cover-launch names the server it started for this run (its port shifted by the domain).
  if (const char* server = std::getenv("COVER_DDS_DISCOVERY_SERVER"); server && *server) {
    options.discovery_server = server;
  }
  if (const char* identity = std::getenv(kIdentityEnvironment); identity && *identity) {
    options.security.identity = identity;
  }
  return options;
}

std::string profile_from_environment(const std::string& fallback) {
  const char* profile = std::getenv("COVER_DDS_PROFILE");
  return profile && *profile ? std::string(profile) : fallback;
}

}  // namespace cover::dds
