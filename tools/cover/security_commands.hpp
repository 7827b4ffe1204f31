#pragma once

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

// `cover security check DIR`: per identity, what it may publish/subscribe and when it
// expires. Exit 0 when every identity is valid, 1 when one is broken, expired or
// mis-signed (each named), 2 when DIR is not a fleet directory.
int security_check(const std::string& directory, bool json);

}  // namespace cover::cli
