#include "cover/mavlink/connection_url.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace cover::mavlink {
namespace {

// The message of the exception parse throws for `text` ("" when it does not throw).
std::string parse_error(const std::string& text) {
  try {
    ConnectionUrl::parse(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ConnectionUrl, UdpInAsMavsdkWritesIt) {
  const auto url = ConnectionUrl::parse("udpin://0.0.0.0:14540");
  EXPECT_EQ(url.kind, ConnectionUrl::Kind::UdpIn);
  EXPECT_EQ(url.host, "0.0.0.0");
  EXPECT_EQ(url.port, 14540);
  EXPECT_EQ(url.to_string(), "udpin://0.0.0.0:14540");
}

TEST(ConnectionUrl, UdpInWithoutHostListensEverywhere) {
  const auto url = ConnectionUrl::parse("udpin://:14541");
  EXPECT_EQ(url.host, "0.0.0.0");
  EXPECT_EQ(url.port, 14541);
}

TEST(ConnectionUrl, UdpOutTakesNamesAndIpv6) {
  auto url = ConnectionUrl::parse("udpout://localhost:14580");
  EXPECT_EQ(url.kind, ConnectionUrl::Kind::UdpOut);
  EXPECT_EQ(url.host, "localhost");
  EXPECT_EQ(url.port, 14580);
  url = ConnectionUrl::parse("udpout://[::1]:14580");
  EXPECT_EQ(url.host, "::1");
  EXPECT_EQ(url.to_string(), "udpout://[::1]:14580");
}

TEST(ConnectionUrl, TcpServerAndClient) {
  auto url = ConnectionUrl::parse("tcpin://0.0.0.0:4560");
  EXPECT_EQ(url.kind, ConnectionUrl::Kind::TcpIn);
  EXPECT_EQ(url.host, "0.0.0.0");
  EXPECT_EQ(url.port, 4560);
  EXPECT_EQ(url.to_string(), "tcpin://0.0.0.0:4560");
  url = ConnectionUrl::parse("tcpin://:4561");
  EXPECT_EQ(url.host, "0.0.0.0");
  url = ConnectionUrl::parse("tcp://localhost:5760");
  EXPECT_EQ(url.kind, ConnectionUrl::Kind::TcpOut);
  EXPECT_EQ(url.host, "localhost");
  EXPECT_EQ(url.to_string(), "tcp://localhost:5760");
  EXPECT_EQ(ConnectionUrl::parse("tcpout://[::1]:5760").to_string(), "tcp://[::1]:5760");
}

TEST(ConnectionUrl, SerialWithAndWithoutBaud) {
  auto url = ConnectionUrl::parse("serial:///dev/ttyACM0:921600");
  EXPECT_EQ(url.kind, ConnectionUrl::Kind::Serial);
  EXPECT_EQ(url.device, "/dev/ttyACM0");
  EXPECT_EQ(url.baud, 921600);
  EXPECT_EQ(url.to_string(), "serial:///dev/ttyACM0:921600");
  url = ConnectionUrl::parse("serial:///dev/serial/by-id/usb-Holybro_Pixhawk6C-if00");
  EXPECT_EQ(url.device, "/dev/serial/by-id/usb-Holybro_Pixhawk6C-if00");
  EXPECT_EQ(url.baud, 57600);
}

TEST(ConnectionUrl, BadFormsSayWhatIsWrongAndWhatIsAccepted) {
  const struct {
    const char* text;
    const char* says;
  } cases[] = {
      {"0.0.0.0:14540", "no scheme"},
      {"udp://:14540", "say udpin:// (listen) or udpout://"},
      {"tcp://:5760", "tcp needs the host"},
      {"tcpin://0.0.0.0:99999", "port 99999 is out of range 0..65535"},
      {"mavlink://x:1", "unknown scheme 'mavlink'"},
      {"udpin://0.0.0.0", "no :PORT"},
      {"udpin://0.0.0.0:port", "port 'port' is not a number"},
      {"udpin://0.0.0.0:70000", "port 70000 is out of range 0..65535"},
      {"udpout://:14580", "udpout needs the host"},
      {"udpout://1.2.3.4:0", "port 0 is out of range 1..65535"},
      {"udpout://::1:14580", "IPv6 address needs brackets"},
      {"udpout://[::1:14580", "unclosed '['"},
      {"serial://dev/ttyS0:57600", "absolute device path"},
      {"serial:///dev/ttyS0:12345", "baud rate 12345 is not one of 9600"},
      {"serial:///dev/ttyS0:fast", "baud rate 'fast' is not a number"},
      {"serial:///dev/:57600", "no serial device"},
  };
  for (const auto& c : cases) {
    const std::string error = parse_error(c.text);
    EXPECT_NE(error.find(c.says), std::string::npos) << c.text << " -> " << error;
    EXPECT_NE(error.find("udpin://IP:PORT"), std::string::npos) << c.text << " -> " << error;
  }
}

}  // namespace
}  // namespace cover::mavlink
