#pragma once

#include <string>

namespace cover::dds {

// DDS-Security for one participant: which fleet directory (made by `cover security
// init`) and which identity in it. Off by default (the local simulator); config/dds.yaml
// `dds.security`, a profile's `security`, --security/--identity or
// $COVER_DDS_SECURITY/$COVER_DDS_IDENTITY turn it on. docs/security.md.
struct SecurityOptions {
  bool enabled = false;
  std::string directory;  // the fleet directory
  std::string identity;   // e.g. "uav-agent-0" (access_rules.hpp names them)
  // A process warns at start-up, and `cover security check` fails, when its identity (its
  // certificate, its permissions or the CA) expires within this many days: time to renew.
  int expiry_warning_days = 14;

  // Throws DdsError naming the missing key when enabled without a directory or identity.
  void validate() const;
};

// The highest domain a fleet's governance and permissions cover: Cyclone 0.10's parser
// refuses a domain id above 230 in them (DDS's 0..232 otherwise).
inline constexpr int kMaxSecureDomainId = 230;

// The longest validity `cover security init --days` makes, and so the widest warning window.
inline constexpr int kMaxValidityDays = 3650;

// The environment variables that turn security on with a fleet directory and name the
// identity (cover-launch sets them per process).
inline constexpr const char* kSecurityEnvironment = "COVER_DDS_SECURITY";
inline constexpr const char* kIdentityEnvironment = "COVER_DDS_IDENTITY";

// The files of one identity in a fleet directory, as the DDS-Security plugins take them.
// Layout (written by `cover security init`, read by every participant):
//   DIR/fleet.yaml, DIR/identity_ca.pem, DIR/permissions_ca.pem, DIR/governance.p7s,
//   DIR/identities/NAME/{cert.pem, key.pem, permissions.p7s}; DIR/ca.key (the CA's
//   private key, needed only to sign: keep it off the vehicles).
struct SecurityFiles {
  std::string fleet;
  std::string identity_ca;
  std::string permissions_ca;
  std::string governance;
  std::string certificate;
  std::string private_key;
  std::string permissions;

  static SecurityFiles of(const std::string& directory, const std::string& identity);
};

// The layout's names, shared by `cover security init` and SecurityFiles::of.
namespace security_layout {
inline constexpr const char* kFleet = "fleet.yaml";
inline constexpr const char* kIdentityCa = "identity_ca.pem";
inline constexpr const char* kPermissionsCa = "permissions_ca.pem";
inline constexpr const char* kCaKey = "ca.key";
inline constexpr const char* kGovernanceXml = "governance.xml";
inline constexpr const char* kGovernance = "governance.p7s";
inline constexpr const char* kIdentities = "identities";
inline constexpr const char* kCertificate = "cert.pem";
inline constexpr const char* kPrivateKey = "key.pem";
inline constexpr const char* kPermissionsXml = "permissions.xml";
inline constexpr const char* kPermissions = "permissions.p7s";
}  // namespace security_layout

}  // namespace cover::dds
