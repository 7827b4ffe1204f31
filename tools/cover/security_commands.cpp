// `cover security init|check`. Keys and certificates are made by the openssl command
// line (run without a shell, private keys created 0600 under umask 077, never printed);
// the check reads them back with the same code every participant uses at start-up.
#include "security_commands.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "cover/config/yaml_reader.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/dds/participant_options.hpp"
#include "cover/dds/security_check.hpp"
#include "cover/dds/security_options.hpp"
#include "cover/dds/vendor.hpp"
#include "cover/process/child_process.hpp"
#include "security_documents.hpp"

namespace cover::cli {
namespace {

namespace fs = std::filesystem;
namespace layout = dds::security_layout;

constexpr int kExitBroken = 1;
constexpr int kExitUsage = 2;
constexpr int kExitOpenssl = 3;
constexpr int kExitExpiring = 4;
constexpr std::uint32_t kMaxPerRole = 64;  // identities per numbered role
constexpr const char* kOrganisation = "COVER";

struct OpensslError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string find_openssl() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path candidate = fs::path(dir) / "openssl";
    if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  throw OpensslError("the openssl command is not installed (scripts/setup installs it)");
}

// Runs openssl with `args`; its messages go to `log` (they hold no key material).
void openssl(const std::vector<std::string>& args, const fs::path& log) {
  static const std::string binary = find_openssl();
  std::vector<std::string> argv{binary};
  argv.insert(argv.end(), args.begin(), args.end());
  process::SpawnOptions options;
  options.null_stdin = true;
  options.log_file = log.string();
  options.close_other_fds = true;
  process::ChildProcess child(argv, options);
  const auto code = child.wait(std::chrono::seconds(60));
  if (code != 0) {
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    throw OpensslError("openssl " + args.at(0) + " failed:\n" + text.str());
  }
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string utc(std::time_t t, const char* format) {
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof(text), format, &tm);
  return text;
}

std::string random_serial() {
  std::random_device device;
  std::ostringstream hex;
  // A leading 1: positive and never zero, as X.509 serials must be.
  hex << "0x1" << std::hex << ((static_cast<std::uint64_t>(device()) << 32) | device());
  return hex.str();
}

void new_key(const fs::path& key, const fs::path& log) {
  openssl({"genpkey", "-algorithm", "EC", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-out",
           key.string()},
          log);
  fs::permissions(key, fs::perms::owner_read | fs::perms::owner_write);
}

void sign(const fs::path& document, const fs::path& signed_document, const fs::path& dir,
          const fs::path& log) {
  openssl({"smime", "-sign", "-in", document.string(), "-text", "-out", signed_document.string(),
           "-signer", (dir / layout::kPermissionsCa).string(), "-inkey",
           (dir / layout::kCaKey).string()},
          log);
}

void make_ca(const fs::path& dir, int days, const fs::path& log) {
  new_key(dir / layout::kCaKey, log);
  openssl({"req", "-x509", "-new", "-key", (dir / layout::kCaKey).string(), "-subj",
           std::string("/O=") + kOrganisation + "/CN=COVER fleet CA", "-days", std::to_string(days),
           "-sha256", "-out", (dir / layout::kIdentityCa).string()},
          log);
  // One CA signs both identities and permissions; the plugins take two files.
  fs::copy_file(dir / layout::kIdentityCa, dir / layout::kPermissionsCa);
}

void make_identity(const fs::path& dir, const dds::Identity& identity,
                   const SecurityInitRequest& request, std::time_t now, const fs::path& log) {
  const std::string name = dds::identity_name(identity);
  const fs::path own = dir / layout::kIdentities / name;
  fs::create_directories(own);
  new_key(own / layout::kPrivateKey, log);
  const fs::path csr = own / "request.csr";
  openssl({"req", "-new", "-key", (own / layout::kPrivateKey).string(), "-subj",
           std::string("/O=") + kOrganisation + "/CN=" + name, "-out", csr.string()},
          log);
  openssl({"x509", "-req", "-in", csr.string(), "-CA", (dir / layout::kIdentityCa).string(),
           "-CAkey", (dir / layout::kCaKey).string(), "-set_serial", random_serial(), "-days",
           std::to_string(request.days), "-sha256", "-out", (own / layout::kCertificate).string()},
          log);
  fs::remove(csr);
  // As `openssl x509 -noout -subject -nameopt RFC2253` prints it (verified afterwards).
  const std::string subject = "CN=" + name + ",O=" + kOrganisation;
  const char* format = "%Y-%m-%dT%H:%M:%S";
  const std::string xml = permissions_xml(
      name, subject, utc(now, format), utc(now + std::time_t{request.days} * 86400, format),
      dds::topic_access(identity, request.fleet), dds::kMaxSecureDomainId);
  write_text(own / layout::kPermissionsXml, xml);
  sign(own / layout::kPermissionsXml, own / layout::kPermissions, dir, log);
}

void write_fleet_record(const fs::path& dir, const SecurityInitRequest& request, std::time_t now) {
  std::ostringstream yaml;
  yaml << "# Written by `cover security init`; read by every secure participant.\n"
       << "fleet:\n"
       << "  # Every process of this fleet runs this DDS vendor (docs/security.md).\n"
       << "  vendor: " << request.vendor << "\n"
       << "  ugvs: " << request.fleet.ugvs << "\n"
       << "  uavs: " << request.fleet.uavs << "\n"
       << "  ground_stations: " << request.fleet.ground_stations << "\n"
       << "  created_utc: \"" << utc(now, "%Y-%m-%dT%H:%M:%SZ") << "\"\n"
       << "  days: " << request.days << "\n";
  write_text(dir / layout::kFleet, yaml.str());
}

void check_request(const SecurityInitRequest& request) {
  if (request.days < 1 || request.days > dds::kMaxValidityDays) {
    throw std::invalid_argument("--days " + std::to_string(request.days) + " (valid: 1.." +
                                std::to_string(dds::kMaxValidityDays) + ")");
  }
  dds::parse_vendor(request.vendor);
  const dds::Fleet& fleet = request.fleet;
  if (fleet.ugvs > kMaxPerRole || fleet.uavs > kMaxPerRole || fleet.ground_stations > kMaxPerRole) {
    throw std::invalid_argument("--ugvs, --uavs and --ground-stations are 0.." +
                                std::to_string(kMaxPerRole) + " each");
  }
  const fs::path dir(request.directory);
  if (fs::exists(dir) && !(fs::is_directory(dir) && fs::is_empty(dir))) {
    throw std::invalid_argument(request.directory +
                                " exists and is not empty: a fleet directory is never "
                                "overwritten (its keys would be lost); choose a new one");
  }
}

int init(const SecurityInitRequest& request) {
  const fs::path dir = fs::absolute(request.directory);
  const std::time_t now = std::time(nullptr);
  const mode_t old_mask = umask(077);  // keys, and everything else, private by default
  const fs::path log = dir / ".openssl.log";
  try {
    fs::create_directories(dir / layout::kIdentities);
    make_ca(dir, request.days, log);
    write_text(dir / layout::kGovernanceXml, governance_xml(dds::kMaxSecureDomainId));
    sign(dir / layout::kGovernanceXml, dir / layout::kGovernance, dir, log);
    const auto identities = dds::fleet_identities(request.fleet);
    for (const auto& identity : identities) make_identity(dir, identity, request, now, log);
    write_fleet_record(dir, request, now);
    fs::remove(log);
    umask(old_mask);
    // Public documents readable by the processes' users; keys stay 0600.
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      const auto name = entry.path().filename();
      if (entry.is_regular_file() && name != layout::kPrivateKey && name != layout::kCaKey) {
        fs::permissions(entry.path(), fs::perms::owner_read | fs::perms::owner_write |
                                          fs::perms::group_read | fs::perms::others_read);
      }
    }
    for (const auto& identity : identities) {
      dds::verify_identity(dir.string(), dds::identity_name(identity));
    }
    std::cout << "fleet directory " << dir.string() << ": " << identities.size() << " identities, "
              << request.vendor << ", valid " << request.days << " days. Keep " << layout::kCaKey
              << " (the CA's signing key) off the vehicles; give each process only its "
                 "identities/<name> folder and the shared files.\n";
    return 0;
  } catch (...) {
    umask(old_mask);
    throw;
  }
}

// The window of `security.expiry_warning_days`: given, or config/dds.yaml's.
int warning_window_days(const std::optional<int>& given) {
  if (given) {
    if (*given < 0 || *given > dds::kMaxValidityDays) {
      throw dds::DdsError("--warning-days " + std::to_string(*given) + " (valid: 0.." +
                          std::to_string(dds::kMaxValidityDays) + ")");
    }
    return *given;
  }
  return dds::ParticipantOptions::load_file(config::default_config_dir() + "/dds.yaml")
      .security.expiry_warning_days;
}

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const auto& item : items) text += (text.empty() ? "" : " ") + item;
  return text.empty() ? "(nothing)" : text;
}

}  // namespace

int security_init(const SecurityInitRequest& request) {
  try {
    check_request(request);
    return init(request);
  } catch (const OpensslError& e) {
    std::cerr << "cover security init: " << e.what() << "\n";
    return kExitOpenssl;
  } catch (const std::exception& e) {
    std::cerr << "cover security init: " << e.what() << "\n";
    return kExitUsage;
  }
}

int security_check(const std::string& directory, bool json,
                   const std::optional<int>& warning_days) {
  dds::FleetRecord record;
  int window_days = 0;
  try {
    window_days = warning_window_days(warning_days);
    record = dds::read_fleet_record(directory);
  } catch (const std::exception& e) {
    std::cerr << "cover security check: " << e.what() << "\n";
    return kExitUsage;
  }
  bool broken = false;
  bool expiring = false;
  nlohmann::json ca = {{"valid", false}};
  nlohmann::json identities = nlohmann::json::array();
  if (!json) {
    std::cout << "fleet " << directory << ": " << dds::vendor_name(record.vendor) << ", "
              << record.fleet.ugvs << " UGV(s), " << record.fleet.uavs << " UAV(s), "
              << record.fleet.ground_stations << " ground station(s), created "
              << record.created_utc << "; warning window " << window_days << " days\n";
  }
  // An expiry within the window is flagged on its line (and in --json) and fails the check.
  const auto soon = [&](std::int64_t seconds_left) {
    const bool within = dds::expires_within(seconds_left, window_days);
    expiring = expiring || within;
    return within;
  };
  try {
    const dds::CaValidity validity = dds::ca_validity(directory);
    const bool within = soon(validity.seconds_to_expiry);
    ca = {{"valid", validity.seconds_to_expiry > 0},
          {"not_after_utc", validity.not_after_utc},
          {"seconds_to_expiry", validity.seconds_to_expiry},
          {"expires_within_warning", within}};
    broken = broken || validity.seconds_to_expiry <= 0;
    if (!json) {
      std::cout << "CA: valid until " << validity.not_after_utc << " ("
                << dds::time_left_text(validity.seconds_to_expiry) << " left)"
                << (within ? ", EXPIRES WITHIN THE WARNING WINDOW" : "") << "\n";
    }
  } catch (const dds::DdsError& e) {
    broken = true;
    ca["error"] = e.what();
    if (!json) std::cout << "CA: INVALID: " << e.what() << "\n";
  }
  for (const auto& identity : dds::fleet_identities(record.fleet)) {
    const std::string name = dds::identity_name(identity);
    try {
      const dds::IdentityReport report = dds::verify_identity(directory, name);
      const bool within = soon(report.seconds_to_expiry);
      identities.push_back({{"identity", name},
                            {"valid", true},
                            {"subject", report.subject},
                            {"not_before_utc", report.not_before_utc},
                            {"not_after_utc", report.not_after_utc},
                            {"seconds_to_expiry", report.seconds_to_expiry},
                            {"expires_first", report.expires_first},
                            {"expires_within_warning", within},
                            {"publish", report.publish},
                            {"subscribe", report.subscribe}});
      if (!json) {
        std::cout << name << ": valid until " << report.not_after_utc << " ("
                  << dds::time_left_text(report.seconds_to_expiry) << " left, its "
                  << report.expires_first << ")"
                  << (within ? ", EXPIRES WITHIN THE WARNING WINDOW" : "") << "\n"
                  << "  publish:   " << joined(report.publish) << "\n"
                  << "  subscribe: " << joined(report.subscribe) << "\n";
      }
    } catch (const dds::DdsError& e) {
      broken = true;
      identities.push_back({{"identity", name}, {"valid", false}, {"error", e.what()}});
      if (!json) std::cout << name << ": INVALID: " << e.what() << "\n";
    }
  }
  const bool ca_key_present = fs::exists(fs::path(directory) / layout::kCaKey);
  if (json) {
    std::cout << nlohmann::json{{"directory", directory},
                                {"vendor", dds::vendor_name(record.vendor)},
                                {"created_utc", record.created_utc},
                                {"warning_days", window_days},
                                {"ca", ca},
                                {"ca_key_present", ca_key_present},
                                {"identities", identities}}
                     .dump()
              << "\n";
  } else if (ca_key_present) {
    std::cout << "note: " << layout::kCaKey
              << " (the CA's signing key) is in this directory: keep it off the vehicles\n";
  }
  if (broken) return kExitBroken;
  return expiring ? kExitExpiring : 0;
}

}  // namespace cover::cli
