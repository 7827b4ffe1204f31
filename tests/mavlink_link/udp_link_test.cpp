#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <string>

#include "cover/mavlink/connection_url.hpp"
#include "cover/mavlink/link.hpp"
#include "cover/test/time_scale.hpp"

namespace cover::mavlink {
namespace {

using std::chrono::milliseconds;

// A plain loopback UDP socket on an ephemeral port: the other end of the link under test.
class Peer {
 public:
  Peer() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
    socklen_t length = sizeof(address);
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &length);
    port_ = ntohs(address.sin_port);
  }
  ~Peer() { ::close(fd_); }
  std::uint16_t port() const { return port_; }

  // One datagram within 2 s (scaled), its sender remembered for reply().
  std::string receive() {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, 2000 * cover::test::whole_time_scale()) <= 0) return "";
    std::array<char, 512> buffer{};
    sender_length_ = sizeof(sender_);
    const ssize_t n = ::recvfrom(fd_, buffer.data(), buffer.size(), 0,
                                 reinterpret_cast<sockaddr*>(&sender_), &sender_length_);
    return n > 0 ? std::string(buffer.data(), static_cast<std::size_t>(n)) : "";
  }
  void reply(const std::string& text) {
    ::sendto(fd_, text.data(), text.size(), 0, reinterpret_cast<sockaddr*>(&sender_),
             sender_length_);
  }
  void send_to(std::uint16_t port, const std::string& text) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(port);
    ::sendto(fd_, text.data(), text.size(), 0, reinterpret_cast<sockaddr*>(&address),
             sizeof(address));
  }

 private:
  int fd_ = -1;
  std::uint16_t port_ = 0;
  sockaddr_in sender_{};
  socklen_t sender_length_ = 0;
};

// Reads until a datagram arrives or 2 s (scaled) pass.
std::string read_text(Link& link) {
  std::array<std::uint8_t, 512> buffer{};
  for (int i = 0; i < 20 * cover::test::whole_time_scale(); ++i) {
    const std::size_t n = link.read(buffer.data(), buffer.size(), milliseconds(100));
    if (n > 0) return std::string(reinterpret_cast<const char*>(buffer.data()), n);
  }
  return "";
}

bool write_text(Link& link, const std::string& text) {
  return link.write(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

// A free loopback port for a udpin link: bound and released (the kernel does not hand it
// out again at once).
std::uint16_t free_port() {
  Peer probe;
  return probe.port();
}

TEST(UdpLink, UdpOutSendsToItsPeerAndHearsTheReply) {
  Peer autopilot;
  auto link =
      make_link(ConnectionUrl::parse("udpout://localhost:" + std::to_string(autopilot.port())));
  ASSERT_TRUE(link->open()) << link->last_error();
  EXPECT_EQ(link->describe(), "udpout://localhost:" + std::to_string(autopilot.port()));
  ASSERT_TRUE(write_text(*link, "hello"));
  EXPECT_EQ(autopilot.receive(), "hello");
  autopilot.reply("heartbeat");
  EXPECT_EQ(read_text(*link), "heartbeat");
}

TEST(UdpLink, UdpInAnswersTheLastSender) {
  const std::uint16_t port = free_port();
  auto link = make_link(ConnectionUrl::parse("udpin://127.0.0.1:" + std::to_string(port)));
  ASSERT_TRUE(link->open()) << link->last_error();
  EXPECT_FALSE(write_text(*link, "too early"));
  EXPECT_NE(link->last_error().find("no peer yet"), std::string::npos) << link->last_error();

  Peer first;
  Peer second;
  first.send_to(port, "from first");
  EXPECT_EQ(read_text(*link), "from first");
  ASSERT_TRUE(write_text(*link, "to first"));
  EXPECT_EQ(first.receive(), "to first");
  second.send_to(port, "from second");
  EXPECT_EQ(read_text(*link), "from second");
  ASSERT_TRUE(write_text(*link, "to second"));
  EXPECT_EQ(second.receive(), "to second");
}

TEST(UdpLink, FixedPeerSendsFirstLikeSitl) {
  Peer companion;
  auto link = make_udp_link("127.0.0.1", 0, "127.0.0.1", companion.port());
  ASSERT_TRUE(link->open()) << link->last_error();
  ASSERT_TRUE(write_text(*link, "heartbeat"));
  EXPECT_EQ(companion.receive(), "heartbeat");
  companion.reply("setpoint");
  EXPECT_EQ(read_text(*link), "setpoint");
}

TEST(UdpLink, ClosedLinkRefusesWritesAndReopens) {
  Peer autopilot;
  auto link =
      make_link(ConnectionUrl::parse("udpout://127.0.0.1:" + std::to_string(autopilot.port())));
  ASSERT_TRUE(link->open());
  link->close();
  EXPECT_FALSE(link->is_open());
  EXPECT_FALSE(write_text(*link, "x"));
  std::array<std::uint8_t, 16> buffer{};
  EXPECT_EQ(link->read(buffer.data(), buffer.size(), milliseconds(1)), 0U);
  ASSERT_TRUE(link->open());
  ASSERT_TRUE(write_text(*link, "again"));
  EXPECT_EQ(autopilot.receive(), "again");
}

TEST(UdpLink, UnreachablePeerIsNotAFailure) {
  const std::uint16_t nobody = free_port();
  auto link = make_link(ConnectionUrl::parse("udpout://127.0.0.1:" + std::to_string(nobody)));
  ASSERT_TRUE(link->open());
  write_text(*link, "anyone?");  // answered by ICMP port unreachable
  std::array<std::uint8_t, 16> buffer{};
  EXPECT_EQ(link->read(buffer.data(), buffer.size(), milliseconds(50)), 0U);
  write_text(*link, "anyone?");
  EXPECT_EQ(link->read(buffer.data(), buffer.size(), milliseconds(50)), 0U);
  EXPECT_TRUE(link->is_open());
}

TEST(UdpLink, UnresolvableHostAndTakenPortAreClearErrors) {
  auto link = make_link(ConnectionUrl::parse("udpout://no-such-host.invalid:14580"));
  EXPECT_FALSE(link->open());
  EXPECT_NE(link->last_error().find("cannot resolve 'no-such-host.invalid'"), std::string::npos)
      << link->last_error();
  Peer holder;
  auto taken =
      make_link(ConnectionUrl::parse("udpin://127.0.0.1:" + std::to_string(holder.port())));
  EXPECT_FALSE(taken->open());
  EXPECT_NE(taken->last_error().find("cannot bind"), std::string::npos) << taken->last_error();
}

}  // namespace
}  // namespace cover::mavlink
