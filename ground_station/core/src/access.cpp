#include "cover/ground_station/access.hpp"

#include <cctype>
#include <fstream>
#include <random>
#include <stdexcept>

namespace cover::ground_station {
namespace {

// The value of `key` in the target's query string, "" when none.
std::string query_value(const std::string& resource, const std::string& key) {
  const auto q = resource.find('?');
  if (q == std::string::npos) return "";
  std::size_t pos = q + 1;
  while (pos <= resource.size()) {
    const auto end = std::min(resource.find('&', pos), resource.size());
    const std::string pair = resource.substr(pos, end - pos);
    const auto eq = pair.find('=');
    if (eq != std::string::npos && pair.substr(0, eq) == key) return pair.substr(eq + 1);
    pos = end + 1;
  }
  return "";
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

}  // namespace

bool same_token(const std::string& a, const std::string& b) {
  if (a.size() != b.size() || a.empty()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

AccessDecision check_request(const AccessPolicy& policy, const std::string& resource,
                             const std::string& authorization, const std::string& host,
                             const std::string& origin) {
  AccessDecision d;
  const std::string bearer = "Bearer ";
  std::string offered = query_value(resource, "token");
  if (offered.empty() && authorization.compare(0, bearer.size(), bearer) == 0)
    offered = trim(authorization.substr(bearer.size()));
  d.has_token = same_token(offered, policy.token);
  if (!offered.empty() && !d.has_token) {
    d.status = 401;
    d.message = "wrong token";
    return d;
  }
  if (policy.token_required && !d.has_token) {
    d.status = 401;
    d.message = "this ground station needs its token (?token=... as printed at its start)";
    return d;
  }
  if (host.empty()) {
    d.status = 400;
    d.message = "no Host header";
    return d;
  }
  if (!origin.empty() && origin != "http://" + host) {
    d.status = 403;
    d.message = "Origin " + origin.substr(0, 100) + " is not this ground station (http://" +
                host.substr(0, 100) + ")";
    return d;
  }
  return d;
}

bool is_loopback(const std::string& address) {
  return address == "localhost" || address == "::1" || address.rfind("127.", 0) == 0;
}

std::string make_token() {
  std::random_device random;
  static const char* hex = "0123456789abcdef";
  std::string token;
  for (int i = 0; i < 32; ++i) token += hex[random() & 0xf];
  return token;
}

std::string read_token_file(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line)) throw std::runtime_error(path + ": cannot read the token");
  line = trim(line);
  if (line.size() < 16) throw std::runtime_error(path + ": a token of at least 16 characters");
  for (const char c : line) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_')
      throw std::runtime_error(path + ": the token may hold letters, digits, '-' and '_' only");
  }
  return line;
}

std::optional<std::string> static_file(const std::string& resource) {
  std::string path = resource.substr(0, resource.find('?'));
  if (path.empty() || path[0] != '/') return std::nullopt;
  if (path == "/") return std::string("index.html");
  path = path.substr(1);
  std::size_t start = 0;
  while (start <= path.size()) {
    const auto end = std::min(path.find('/', start), path.size());
    const std::string segment = path.substr(start, end - start);
    if (segment.empty() || segment[0] == '.') return std::nullopt;
    for (const char c : segment) {
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-')
        return std::nullopt;
    }
    start = end + 1;
  }
  return path;
}

const char* content_type(const std::string& file) {
  auto ends = [&](const char* suffix) {
    const std::string s(suffix);
    return file.size() >= s.size() && file.compare(file.size() - s.size(), s.size(), s) == 0;
  };
  if (ends(".html")) return "text/html; charset=utf-8";
  if (ends(".js")) return "text/javascript; charset=utf-8";
  if (ends(".css")) return "text/css; charset=utf-8";
  if (ends(".png")) return "image/png";
  if (ends(".svg")) return "image/svg+xml";
  if (ends(".json") || ends(".map")) return "application/json";
  return "application/octet-stream";
}

}  // namespace cover::ground_station
