// Checks a fleet directory's files with libcrypto, the way the DDS-Security plugins will
// load them, so that a bad file is a clear error at start-up rather than a participant
// the vendor refuses with a log line, or one that silently matches nobody.
#include "cover/dds/security_check.hpp"

#include <sys/stat.h>

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <memory>
#include <sstream>

#include "cover/config/yaml_reader.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/dds/security_options.hpp"

namespace cover::dds {
namespace {

template <typename T, void (*Free)(T*)>
struct Deleter {
  void operator()(T* p) const { Free(p); }
};
using Bio = std::unique_ptr<BIO, Deleter<BIO, BIO_free_all>>;
using Cert = std::unique_ptr<X509, Deleter<X509, X509_free>>;
using Key = std::unique_ptr<EVP_PKEY, Deleter<EVP_PKEY, EVP_PKEY_free>>;
using Store = std::unique_ptr<X509_STORE, Deleter<X509_STORE, X509_STORE_free>>;
using StoreCtx = std::unique_ptr<X509_STORE_CTX, Deleter<X509_STORE_CTX, X509_STORE_CTX_free>>;
using Pkcs7 = std::unique_ptr<PKCS7, Deleter<PKCS7, PKCS7_free>>;

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw DdsError("security: " + path + ": " + why);
}

// The last libcrypto error as text (cleared), for messages.
std::string crypto_error() {
  const unsigned long code = ERR_get_error();
  ERR_clear_error();
  if (code == 0) return "unknown libcrypto error";
  char text[256];
  ERR_error_string_n(code, text, sizeof(text));
  return text;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot read: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Bio memory_bio(const std::string& data) {
  return Bio(BIO_new_mem_buf(data.data(), static_cast<int>(data.size())));
}

Cert read_certificate(const std::string& path) {
  const std::string pem = read_file(path);
  Bio bio = memory_bio(pem);
  Cert cert(PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr));
  if (!cert) fail(path, "not a PEM certificate (" + crypto_error() + ")");
  return cert;
}

// No passphrase prompt: an encrypted key is refused instead of blocking a daemon.
int no_passphrase(char*, int, int, void*) {
  return -1;
}

Key read_private_key(const std::string& path) {
  struct stat info {};
  if (stat(path.c_str(), &info) != 0)
    fail(path, std::string("cannot read: ") + std::strerror(errno));
  if ((info.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof(mode), "%04o", static_cast<unsigned>(info.st_mode & 07777));
    fail(path, std::string("private key is accessible to group or others (mode ") + mode +
                   "); run chmod 600 on it");
  }
  const std::string pem = read_file(path);
  Bio bio = memory_bio(pem);
  Key key(PEM_read_bio_PrivateKey(bio.get(), nullptr, &no_passphrase, nullptr));
  if (!key) fail(path, "not an unencrypted PEM private key");
  return key;
}

Store store_of(const X509* ca) {
  Store store(X509_STORE_new());
  X509_STORE_add_cert(store.get(), const_cast<X509*>(ca));
  return store;
}

void verify_against(const X509* ca, X509* cert, const std::string& path,
                    const std::string& ca_path) {
  Store store = store_of(ca);
  StoreCtx ctx(X509_STORE_CTX_new());
  X509_STORE_CTX_init(ctx.get(), store.get(), cert, nullptr);
  if (X509_verify_cert(ctx.get()) != 1) {
    fail(path, std::string("certificate not accepted by ") + ca_path + ": " +
                   X509_verify_cert_error_string(X509_STORE_CTX_get_error(ctx.get())));
  }
}

// The signed content of an S/MIME file, after checking its signature by `ca`.
std::string verified_content(const std::string& path, const X509* ca, const std::string& ca_path) {
  const std::string smime = read_file(path);
  Bio in = memory_bio(smime);
  BIO* detached = nullptr;
  Pkcs7 p7(SMIME_read_PKCS7(in.get(), &detached));
  Bio content(detached);
  if (!p7) fail(path, "not an S/MIME signed document (" + crypto_error() + ")");
  Store store = store_of(ca);
  Bio out(BIO_new(BIO_s_mem()));
  if (PKCS7_verify(p7.get(), nullptr, store.get(), content.get(), out.get(), PKCS7_TEXT) != 1) {
    fail(path, "signature not accepted by " + ca_path + " (" + crypto_error() + ")");
  }
  char* data = nullptr;
  const long size = BIO_get_mem_data(out.get(), &data);
  return std::string(data, static_cast<std::size_t>(size));
}

std::string rfc2253(const X509_NAME* name) {
  Bio bio(BIO_new(BIO_s_mem()));
  X509_NAME_print_ex(bio.get(), name, 0, XN_FLAG_RFC2253);
  char* data = nullptr;
  const long size = BIO_get_mem_data(bio.get(), &data);
  return std::string(data, static_cast<std::size_t>(size));
}

std::string iso8601(std::time_t t) {
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

std::time_t to_time(const ASN1_TIME* time) {
  std::tm tm{};
  ASN1_TIME_to_tm(time, &tm);
  return timegm(&tm);
}

// The text of every <tag>...</tag> inside `xml` (the permissions are ours: flat, no CDATA).
std::vector<std::string> elements(const std::string& xml, const std::string& tag) {
  std::vector<std::string> found;
  const std::string open = "<" + tag + ">", close = "</" + tag + ">";
  for (std::size_t at = xml.find(open); at != std::string::npos; at = xml.find(open, at)) {
    const std::size_t begin = at + open.size();
    const std::size_t end = xml.find(close, begin);
    if (end == std::string::npos) break;
    found.push_back(xml.substr(begin, end - begin));
    at = end;
  }
  return found;
}

std::string section(const std::string& xml, const std::string& tag) {
  const auto all = elements(xml, tag);
  return all.empty() ? "" : all.front();
}

// "YYYY-MM-DDTHH:MM:SS" (UTC) as in <validity>; -1 when malformed.
std::time_t parse_xml_time(const std::string& text) {
  std::tm tm{};
  const char* end = strptime(text.c_str(), "%Y-%m-%dT%H:%M:%S", &tm);
  return end && (*end == '\0' || *end == 'Z') ? timegm(&tm) : static_cast<std::time_t>(-1);
}

void check_permissions(const std::string& xml, const std::string& subject, const std::string& path,
                       IdentityReport& report, std::time_t& not_after) {
  const std::string named = section(xml, "subject_name");
  if (named != subject) {
    fail(path,
         "permissions are for '" + named + "', not this certificate's subject '" + subject + "'");
  }
  const std::time_t begin = parse_xml_time(section(xml, "not_before"));
  const std::time_t end = parse_xml_time(section(xml, "not_after"));
  if (begin < 0 || end < 0) fail(path, "permissions have no valid <validity> period");
  const std::time_t now = std::time(nullptr);
  if (now < begin) fail(path, "permissions not valid before " + iso8601(begin));
  if (now > end) fail(path, "permissions expired on " + iso8601(end));
  not_after = std::min(not_after, end);
  report.publish = elements(section(xml, "publish"), "topic");
  report.subscribe = elements(section(xml, "subscribe"), "topic");
}

}  // namespace

FleetRecord read_fleet_record(const std::string& directory) {
  const std::string path = SecurityFiles::of(directory, "").fleet;
  FleetRecord record;
  try {
    config::YamlReader fleet = config::open_section(path, "fleet", /*required=*/true);
    std::string vendor;
    fleet.require("vendor", vendor);
    fleet.optional("ugvs", record.fleet.ugvs);
    fleet.optional("uavs", record.fleet.uavs);
    fleet.optional("ground_stations", record.fleet.ground_stations);
    fleet.optional("created_utc", record.created_utc);
    fleet.optional("days", record.days);
    fleet.reject_unknown_keys();
    record.vendor = parse_vendor(vendor);
  } catch (const std::exception& e) {
    fail(path, e.what());
  }
  return record;
}

IdentityReport verify_identity(const std::string& directory, const std::string& name) {
  if (!parse_identity(name)) {
    throw DdsError("security: '" + name +
                   "' is not an identity name (sim, task-manager, ugv-agent-K, uav-agent-U, "
                   "ground-station-N)");
  }
  const SecurityFiles files = SecurityFiles::of(directory, name);
  IdentityReport report;
  report.name = name;
  const Cert identity_ca = read_certificate(files.identity_ca);
  const Cert permissions_ca = read_certificate(files.permissions_ca);
  const Cert cert = read_certificate(files.certificate);
  verify_against(identity_ca.get(), cert.get(), files.certificate, files.identity_ca);
  const Key key = read_private_key(files.private_key);
  if (X509_check_private_key(cert.get(), key.get()) != 1) {
    ERR_clear_error();
    fail(files.private_key, "does not belong to " + files.certificate);
  }
  report.subject = rfc2253(X509_get_subject_name(cert.get()));
  report.not_before_utc = iso8601(to_time(X509_get0_notBefore(cert.get())));
  std::time_t not_after = to_time(X509_get0_notAfter(cert.get()));
  report.expires_first = "certificate";
  verified_content(files.governance, permissions_ca.get(), files.permissions_ca);
  const std::string permissions =
      verified_content(files.permissions, permissions_ca.get(), files.permissions_ca);
  const std::time_t certificate_not_after = not_after;
  check_permissions(permissions, report.subject, files.permissions, report, not_after);
  if (not_after < certificate_not_after) report.expires_first = "permissions";
  // Nothing the CA signed is accepted after the CA itself expires.
  for (const Cert* ca : {&identity_ca, &permissions_ca}) {
    const std::time_t ca_not_after = to_time(X509_get0_notAfter(ca->get()));
    if (ca_not_after < not_after) {
      not_after = ca_not_after;
      report.expires_first = "CA";
    }
  }
  report.not_after_utc = iso8601(not_after);
  report.seconds_to_expiry = static_cast<std::int64_t>(not_after - std::time(nullptr));
  return report;
}

CaValidity ca_validity(const std::string& directory) {
  const std::string path = SecurityFiles::of(directory, "").identity_ca;
  const Cert ca = read_certificate(path);
  CaValidity validity;
  validity.not_before_utc = iso8601(to_time(X509_get0_notBefore(ca.get())));
  const std::time_t not_after = to_time(X509_get0_notAfter(ca.get()));
  validity.not_after_utc = iso8601(not_after);
  validity.seconds_to_expiry = static_cast<std::int64_t>(not_after - std::time(nullptr));
  return validity;
}

bool expires_within(std::int64_t seconds_to_expiry, int days) {
  return seconds_to_expiry < std::int64_t{days} * 86400;
}

std::string time_left_text(std::int64_t seconds) {
  if (seconds <= 0) return "expired";
  const std::int64_t minutes = seconds / 60;
  return std::to_string(minutes / 1440) + " d " + std::to_string(minutes / 60 % 24) + " h " +
         std::to_string(minutes % 60) + " min";
}

std::string expiry_warning(const IdentityReport& report, int warning_days) {
  if (!expires_within(report.seconds_to_expiry, warning_days)) return "";
  return "security: identity " + report.name + " expires on " + report.not_after_utc + " (its " +
         report.expires_first + "), in " + time_left_text(report.seconds_to_expiry) +
         ": within security.expiry_warning_days (" + std::to_string(warning_days) +
         "); renew the fleet directory and restart before then (docs/security.md)";
}

std::optional<IdentityReport> check_participant_security(const ParticipantOptions& options) {
  const SecurityOptions& security = options.security;
  security.validate();
  if (!security.enabled) return std::nullopt;
  if (options.domain_id > kMaxSecureDomainId) {
    throw DdsError("security: domain " + std::to_string(options.domain_id) +
                   " is above the secure range 0.." + std::to_string(kMaxSecureDomainId));
  }
  const FleetRecord record = read_fleet_record(security.directory);
  if (record.vendor != options.vendor) {
    throw DdsError(std::string("security: fleet ") + security.directory + " runs " +
                   vendor_name(record.vendor) + ", this process " + vendor_name(options.vendor) +
                   ": a secure fleet runs one vendor, because Fast DDS 2.9 and Cyclone DDS 0.10 "
                   "complete the DDS-Security handshake with each other only in some "
                   "certificate pairings (docs/security.md); use --dds " +
                   vendor_name(record.vendor) + " or a fleet directory made with --vendor " +
                   vendor_name(options.vendor));
  }
  return verify_identity(security.directory, security.identity);
}

}  // namespace cover::dds
