#pragma once

#include <string>
#include <vector>

#include "cover/dds/participant_options.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace cover::dds {

// The DDS flags every COVER command line shares: --dds, --domain, --dds-config,
// --dds-profile, --security, --identity. Precedence: flag > environment ($COVER_DDS,
// $COVER_DDS_DOMAIN, $COVER_DDS_PROFILE, $COVER_DDS_SECURITY, $COVER_DDS_IDENTITY) >
// config file.
// In its own library (cover_dds_cli) so that users of the DDS layer do not compile
// CLI11 or the YAML reader.
struct DdsCliOptions {
  std::string vendor;
  int domain_id = 0;
  std::string config_path;         // default: config/dds.yaml of the shipped configuration
  std::string profile;             // a `dds.profiles` entry of config_path; empty: none
  std::string security_directory;  // a fleet directory: turns DDS-Security on
  std::string identity;            // this process's identity in it

  DdsCliOptions();
  void add_to(CLI::App& app);

  // Throws ConfigError with a clear message, also when security is on and the identity's
  // files are missing, unreadable, expired or mis-signed (checked here, at start-up).
  ParticipantOptions resolve(const std::string& participant_name) const;

 private:
  // One per command line it was added to (the `cover` task commands share one set of
  // options): a --domain given to any of them counts.
  std::vector<CLI::Option*> domain_flags_;
};

}  // namespace cover::dds
