#include "cover/dds/security_options.hpp"

#include <filesystem>

#include "cover/dds/dds_error.hpp"

namespace cover::dds {

void SecurityOptions::validate() const {
  if (!enabled) return;
  if (directory.empty()) {
    throw DdsError(
        "security is enabled but no fleet directory is given (dds.security.directory, "
        "--security DIR or $COVER_DDS_SECURITY)");
  }
  if (identity.empty()) {
    throw DdsError(
        "security is enabled but no identity is given (dds.security.identity, --identity NAME "
        "or $COVER_DDS_IDENTITY)");
  }
}

SecurityFiles SecurityFiles::of(const std::string& directory, const std::string& identity) {
  namespace layout = security_layout;
  // Absolute: the plugins take file URIs, which a relative path would not survive.
  const std::string root = std::filesystem::absolute(directory).lexically_normal().string() + "/";
  const std::string own = root + layout::kIdentities + "/" + identity + "/";
  return {root + layout::kFleet,      root + layout::kIdentityCa, root + layout::kPermissionsCa,
          root + layout::kGovernance, own + layout::kCertificate, own + layout::kPrivateKey,
          own + layout::kPermissions};
}

}  // namespace cover::dds
