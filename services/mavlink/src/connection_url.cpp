#include "cover/mavlink/connection_url.hpp"

#include <cctype>
#include <stdexcept>

#include "serial_baud.hpp"

namespace cover::mavlink {
namespace {

constexpr const char* kForms =
    "expected udpin://IP:PORT (listen), udpout://HOST:PORT (send to), "
    "tcpin://IP:PORT (TCP server), tcp://HOST:PORT (TCP client) or serial:///dev/ttyX:BAUD";
constexpr int kDefaultSerialBaud = 57600;  // MAVSDK's default when the URL names none

[[noreturn]] void fail(const std::string& text, const std::string& why) {
  throw std::invalid_argument("connection URL '" + text + "': " + why + " (" + kForms + ")");
}

bool all_digits(const std::string& s) {
  if (s.empty()) return false;
  for (const char c : s) {
    if (std::isdigit(static_cast<unsigned char>(c)) == 0) return false;
  }
  return true;
}

// A decimal number in [min, max], or a failure naming `what`.
long parse_number(const std::string& text, const std::string& digits, const std::string& what,
                  long min, long max) {
  if (!all_digits(digits) || digits.size() > 9) {
    fail(text, what + " '" + digits + "' is not a number");
  }
  const long value = std::stol(digits);
  if (value < min || value > max) {
    fail(text, what + " " + digits + " is out of range " + std::to_string(min) + ".." +
                   std::to_string(max));
  }
  return value;
}

// "HOST:PORT" or "[IPv6]:PORT" into host and port text.
std::pair<std::string, std::string> split_host_port(const std::string& text,
                                                    const std::string& rest) {
  if (!rest.empty() && rest.front() == '[') {
    const auto close = rest.find(']');
    if (close == std::string::npos) fail(text, "unclosed '[' in the address");
    if (close + 1 >= rest.size() || rest[close + 1] != ':') fail(text, "no :PORT after ']'");
    return {rest.substr(1, close - 1), rest.substr(close + 2)};
  }
  const auto colon = rest.rfind(':');
  if (colon == std::string::npos) fail(text, "no :PORT");
  const std::string host = rest.substr(0, colon);
  if (host.find(':') != std::string::npos) fail(text, "an IPv6 address needs brackets: [::1]:PORT");
  return {host, rest.substr(colon + 1)};
}

ConnectionUrl parse_socket(const std::string& text, const std::string& rest, bool listen,
                           bool tcp) {
  ConnectionUrl url;
  if (tcp) {
    url.kind = listen ? ConnectionUrl::Kind::TcpIn : ConnectionUrl::Kind::TcpOut;
  } else {
    url.kind = listen ? ConnectionUrl::Kind::UdpIn : ConnectionUrl::Kind::UdpOut;
  }
  auto [host, port] = split_host_port(text, rest);
  if (host.empty()) {
    if (!listen) fail(text, std::string(tcp ? "tcp" : "udpout") + " needs the host to reach");
    host = "0.0.0.0";  // MAVSDK's udpin://:14540 listens on every interface
  }
  url.host = host;
  // Port 0 on udpin binds an ephemeral port (tests); a peer on port 0 is not reachable.
  url.port = static_cast<std::uint16_t>(parse_number(text, port, "port", listen ? 0 : 1, 65535));
  return url;
}

ConnectionUrl parse_serial(const std::string& text, const std::string& rest) {
  ConnectionUrl url;
  url.kind = ConnectionUrl::Kind::Serial;
  if (rest.empty() || rest.front() != '/') {
    fail(text, "serial needs an absolute device path: serial:///dev/ttyACM0:921600");
  }
  const auto colon = rest.rfind(':');
  const std::string tail = colon == std::string::npos ? "" : rest.substr(colon + 1);
  if (colon != std::string::npos && rest.find('/', colon) == std::string::npos) {
    url.device = rest.substr(0, colon);
    url.baud = static_cast<int>(parse_number(text, tail, "baud rate", 1, 100000000));
  } else {
    url.device = rest;
    url.baud = kDefaultSerialBaud;
  }
  if (url.device.size() < 2 || url.device.back() == '/') fail(text, "no serial device named");
  if (!detail::termios_speed(url.baud)) {
    fail(text,
         "baud rate " + std::to_string(url.baud) + " is not one of " + detail::kSupportedBauds);
  }
  return url;
}

}  // namespace

ConnectionUrl ConnectionUrl::parse(const std::string& text) {
  const auto scheme_end = text.find("://");
  if (scheme_end == std::string::npos) fail(text, "no scheme");
  const std::string scheme = text.substr(0, scheme_end);
  const std::string rest = text.substr(scheme_end + 3);
  if (scheme == "udpin") return parse_socket(text, rest, true, false);
  if (scheme == "udpout") return parse_socket(text, rest, false, false);
  if (scheme == "tcpin") return parse_socket(text, rest, true, true);
  if (scheme == "tcp" || scheme == "tcpout") return parse_socket(text, rest, false, true);
  if (scheme == "serial") return parse_serial(text, rest);
  if (scheme == "udp") fail(text, "say udpin:// (listen) or udpout:// (send to)");
  fail(text, "unknown scheme '" + scheme + "'");
}

std::string ConnectionUrl::to_string() const {
  if (kind == Kind::Serial) return "serial://" + device + ":" + std::to_string(baud);
  const std::string h = host.find(':') != std::string::npos ? "[" + host + "]" : host;
  const char* scheme = "udpin://";
  if (kind == Kind::UdpOut) scheme = "udpout://";
  if (kind == Kind::TcpIn) scheme = "tcpin://";
  if (kind == Kind::TcpOut) scheme = "tcp://";
  return std::string(scheme) + h + ":" + std::to_string(port);
}

}  // namespace cover::mavlink
