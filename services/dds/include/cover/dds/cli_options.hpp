#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "cover/config/yaml_reader.hpp"
#include "cover/dds/participant_options.hpp"

namespace cover::dds {

// The DDS flags every COVER command line shares: --dds, --domain, --dds-config.
// Precedence: flag > environment ($COVER_DDS, $COVER_DDS_DOMAIN) > config file.
struct DdsCliOptions {
  std::string vendor;
  int domain_id = 0;
  std::string config_path = config::default_config_dir() + "/dds.yaml";

  void add_to(CLI::App& app) {
    app.add_option("--dds", vendor, "DDS vendor: fastdds | cyclone (default: config, $COVER_DDS)");
    domain_flag_ = app.add_option("--domain", domain_id,
                                  "DDS domain id 0..232 (default: config, $COVER_DDS_DOMAIN)");
    app.add_option("--dds-config", config_path, "DDS settings file")->capture_default_str();
  }

  // Throws ConfigError / DdsError with a clear message.
  ParticipantOptions resolve(const std::string& participant_name) const {
    ParticipantOptions options = apply_environment(ParticipantOptions::load_file(config_path));
    if (!vendor.empty()) options.vendor = parse_vendor(vendor);
    if (domain_flag_ && domain_flag_->count() > 0) options.domain_id = domain_id;
    options.participant_name = participant_name;
    options.validate();
    return options;
  }

 private:
  CLI::Option* domain_flag_ = nullptr;
};

}  // namespace cover::dds
