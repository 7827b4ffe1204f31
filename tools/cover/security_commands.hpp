#pragma once

#include <optional>
#include <string>

#include "cover/dds/access_rules.hpp"

namespace cover::cli {

// `cover security init DIR`: a fleet directory (layout: cover/dds/security_options.hpp).
struct SecurityInitRequest {
  std::string directory;  // must not exist yet, or be empty
  dds::Fleet fleet;
  int days = 365;                  // validity of the CA, certificates and permissions
  std::string vendor = "fastdds";  // the one vendor the fleet runs (docs/security.md)
};

// Exit codes: 0 made and checked, 2 bad request or existing directory, 3 openssl failed.
int security_init(const SecurityInitRequest& request);

// `cover security check DIR`: the CA's expiry, and per identity what it may
// publish/subscribe and when it expires. Exit 0 when the CA and every identity are valid
// beyond the warning window (`warning_days`, default config/dds.yaml's
// security.expiry_warning_days), 1 when one is broken, expired or mis-signed (each
// named), 2 when DIR is not a fleet directory, 4 when all are valid but one expires
// within the window (flagged on its line).
int security_check(const std::string& directory, bool json, const std::optional<int>& warning_days);

}  // namespace cover::cli
