#pragma once

#include <optional>
#include <string>

namespace cover::ground_station {

// Who may read the page and who may command the fleet through it.
//  - The token: required on every HTTP and WebSocket request when `token_required` (any bind
//    address but loopback); on loopback the page is readable without it, but every request
//    that moves a vehicle must come over a WebSocket opened with it.
//  - Origin: a browser's request from a page not served by this host (another site's script,
//    DNS rebinding) is refused; a request without Origin is no browser's cross-site one.
struct AccessPolicy {
  std::string token;
  bool token_required = false;
};

struct AccessDecision {
  int status = 200;  // 200, or 401 (token), 403 (Origin), 400 (malformed request)
  std::string message;
  bool has_token = false;  // the request carried the right token
};

// `resource`: the request target ("/ws?token=..."); `authorization`: the header's value
// ("Bearer ..."); `host`: the Host header; `origin`: the Origin header ("" when none).
AccessDecision check_request(const AccessPolicy& policy, const std::string& resource,
                             const std::string& authorization, const std::string& host,
                             const std::string& origin);

// 127.0.0.0/8, ::1 and "localhost": only this host can connect.
bool is_loopback(const std::string& address);
// 32 hex digits from the system's random source.
std::string make_token();
// The first line of a file, surrounding blanks dropped; throws std::runtime_error when it
// cannot be read or holds fewer than 16 characters.
std::string read_token_file(const std::string& path);
// Equal in time independent of where they differ.
bool same_token(const std::string& a, const std::string& b);

// The file a request target names under the served folder ("/" -> "index.html"); nullopt
// for anything but plain names ([A-Za-z0-9._-] segments, no "..", no hidden files).
std::optional<std::string> static_file(const std::string& resource);
const char* content_type(const std::string& file);

}  // namespace cover::ground_station
