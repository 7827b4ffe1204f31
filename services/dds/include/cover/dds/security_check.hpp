#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cover/dds/access_rules.hpp"
#include "cover/dds/participant_options.hpp"
#include "cover/dds/vendor.hpp"

namespace cover::dds {

// What `cover security init` recorded about a fleet directory (DIR/fleet.yaml).
struct FleetRecord {
  // Every process of a secure fleet runs this vendor: Fast DDS 2.9 and Cyclone 0.10 do not
  // complete the DDS-Security handshake reliably with each other (docs/security.md).
  Vendor vendor = Vendor::FastDds;
  Fleet fleet;
  std::string created_utc;
  int days = 0;
};
// Throws DdsError naming the file and key.
FleetRecord read_fleet_record(const std::string& directory);

// One identity after checking every file it needs, as a participant would load them.
struct IdentityReport {
  std::string name;
  std::string subject;                 // RFC 2253, as the permissions must name it
  std::string not_before_utc;          // certificate validity, ISO 8601
  std::string not_after_utc;           // the earlier of certificate and permissions expiry
  std::int64_t seconds_to_expiry = 0;  // from now to not_after_utc
  std::vector<std::string> publish;    // topics, from the signed permissions
  std::vector<std::string> subscribe;
};

// Checks identity `name` of fleet `directory`: every file readable, the private key only
// by its owner and matching the certificate, the certificate signed by the identity CA
// and valid now, governance and permissions signed by the permissions CA, the
// permissions naming this certificate's subject and valid now. Throws DdsError saying
// which file is wrong and why. Never prints key material.
IdentityReport verify_identity(const std::string& directory, const std::string& name);

// A participant's security, checked before the vendor sees it: off, or a valid identity
// whose fleet runs `options.vendor`. Throws DdsError (mixed-vendor secure is refused).
void check_participant_security(const ParticipantOptions& options);

}  // namespace cover::dds
