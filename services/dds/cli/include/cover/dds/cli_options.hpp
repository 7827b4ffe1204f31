#pragma once

#include <string>

#include "cover/dds/participant_options.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace cover::dds {

// The DDS flags every COVER command line shares: --dds, --domain, --dds-config,
// --dds-profile. Precedence: flag > environment ($COVER_DDS, $COVER_DDS_DOMAIN,
// $COVER_DDS_PROFILE) > config file.
// In its own library (cover_dds_cli) so that users of the DDS layer do not compile
// CLI11 or the YAML reader.
struct DdsCliOptions {
  std::string vendor;
  int domain_id = 0;
  std::string config_path;  // default: config/dds.yaml of the shipped configuration
  std::string profile;      // a `dds.profiles` entry of config_path; empty: none

  DdsCliOptions();
  void add_to(CLI::App& app);

  // Throws ConfigError / DdsError with a clear message.
  ParticipantOptions resolve(const std::string& participant_name) const;

 private:
  CLI::Option* domain_flag_ = nullptr;
};

}  // namespace cover::dds
