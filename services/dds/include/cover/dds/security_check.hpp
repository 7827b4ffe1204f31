#pragma once

#include <cstdint>
#include <optional>
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
  std::string not_after_utc;           // the earliest of certificate, permissions and CA expiry
  std::int64_t seconds_to_expiry = 0;  // from now to not_after_utc
  std::string expires_first;           // "certificate", "permissions" or "CA"
  std::vector<std::string> publish;    // topics, from the signed permissions
  std::vector<std::string> subscribe;
};

// Checks identity `name` of fleet `directory`: every file readable, the private key only
// by its owner and matching the certificate, the certificate signed by the identity CA
// and valid now, governance and permissions signed by the permissions CA, the
// permissions naming this certificate's subject and valid now. Throws DdsError saying
// which file is wrong and why. Never prints key material.
IdentityReport verify_identity(const std::string& directory, const std::string& name);

// The fleet CA's certificate (DIR/identity_ca.pem, the one CA of a fleet): its validity.
// Throws DdsError naming the file.
struct CaValidity {
  std::string not_before_utc;
  std::string not_after_utc;
  std::int64_t seconds_to_expiry = 0;
};
CaValidity ca_validity(const std::string& directory);

// True when `seconds_to_expiry` is less than `days` days (or the identity has expired):
// what `security.expiry_warning_days` warns about.
bool expires_within(std::int64_t seconds_to_expiry, int days);
// "12 d 3 h 4 min" (or "expired"), for logs and `cover security check`.
std::string time_left_text(std::int64_t seconds_to_expiry);

// A participant's security, checked before the vendor sees it: off (nullopt), or a valid
// identity whose fleet runs `options.vendor` (its report). Throws DdsError (mixed-vendor
// secure is refused).
std::optional<IdentityReport> check_participant_security(const ParticipantOptions& options);

// One line for the process's log when `report` expires within `warning_days`, else "".
std::string expiry_warning(const IdentityReport& report, int warning_days);

}  // namespace cover::dds
