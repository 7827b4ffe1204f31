#include "cover/dds/cli_options.hpp"

#include <CLI/CLI.hpp>

#include "cover/config/yaml_reader.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/dds/security_check.hpp"

namespace cover::dds {

DdsCliOptions::DdsCliOptions() : config_path(config::default_config_dir() + "/dds.yaml") {}

void DdsCliOptions::add_to(CLI::App& app) {
  app.add_option("--dds", vendor, "DDS vendor: fastdds | cyclone (default: config, $COVER_DDS)");
  domain_flags_.push_back(app.add_option(
      "--domain", domain_id, "DDS domain id 0..232 (default: config, $COVER_DDS_DOMAIN)"));
  app.add_option("--dds-config", config_path, "DDS settings file")->capture_default_str();
  app.add_option("--dds-profile", profile,
                 "Network profile of the DDS settings file, e.g. wifi (default: "
                 "$COVER_DDS_PROFILE, else none)");
  app.add_option("--security", security_directory,
                 "DDS-Security fleet directory (cover security init); turns security on "
                 "(default: $COVER_DDS_SECURITY, else dds.security of the settings file)");
  app.add_option("--identity", identity,
                 "This process's identity in the fleet directory, e.g. uav-agent-0 (default: "
                 "$COVER_DDS_IDENTITY, else dds.security.identity)");
}

ParticipantOptions DdsCliOptions::resolve(const std::string& participant_name) const {
  ParticipantOptions options = apply_environment(ParticipantOptions::load_file(
      config_path, profile.empty() ? profile_from_environment("") : profile));
  if (!vendor.empty()) options.vendor = parse_vendor(vendor);
  for (const CLI::Option* flag : domain_flags_) {
    if (flag->count() > 0) options.domain_id = domain_id;
  }
  if (!security_directory.empty()) {
    options.security.enabled = true;
    options.security.directory = security_directory;
  }
  if (!identity.empty()) options.security.identity = identity;
  options.participant_name = participant_name;
  // A security problem is a configuration error (exit 2 in every process), never a
  // plain participant.
  try {
    check_participant_security(options);
  } catch (const DdsError& e) {
    throw config::ConfigError(e.what());
  }
  options.validate();
  return options;
}

}  // namespace cover::dds
