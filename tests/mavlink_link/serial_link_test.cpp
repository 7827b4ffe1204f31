#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <filesystem>
#include <string>

#include "cover/mavlink/connection_url.hpp"
#include "cover/mavlink/link.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"

namespace cover::mavlink {
namespace {

using std::chrono::milliseconds;

// A pty pair whose slave is reached through a symlink in the scratch folder: the "serial
// cable". The test holds the master (the autopilot's end).
struct Cable {
  int master = -1;
  int slave = -1;
  std::string path = test::scratch_path("ttyFC");
  Cable() {
    EXPECT_EQ(::openpty(&master, &slave, nullptr, nullptr, nullptr), 0);
    std::filesystem::remove(path);
    std::filesystem::create_symlink(::ttyname(slave), path);
  }
  // Pulled: the master closed, the symlink gone.
  void pull() {
    if (master >= 0) ::close(master);
    if (slave >= 0) ::close(slave);
    master = slave = -1;
    std::filesystem::remove(path);
  }
  ~Cable() { pull(); }
  std::string receive() {
    pollfd p{master, POLLIN, 0};
    if (::poll(&p, 1, 2000 * cover::test::whole_time_scale()) <= 0) return "";
    std::array<char, 256> buffer{};
    const ssize_t n = ::read(master, buffer.data(), buffer.size());
    return n > 0 ? std::string(buffer.data(), static_cast<std::size_t>(n)) : "";
  }
};

std::string read_text(Link& link) {
  std::array<std::uint8_t, 256> buffer{};
  for (int i = 0; i < 20 * cover::test::whole_time_scale() && link.is_open(); ++i) {
    const std::size_t n = link.read(buffer.data(), buffer.size(), milliseconds(100));
    if (n > 0) return std::string(reinterpret_cast<const char*>(buffer.data()), n);
  }
  return "";
}

bool write_text(Link& link, const std::string& text) {
  return link.write(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

TEST(SerialLink, RawBytesBothWaysThroughAPty) {
  Cable cable;
  auto link = make_link(ConnectionUrl::parse("serial://" + cable.path + ":921600"));
  ASSERT_TRUE(link->open()) << link->last_error();
  // Raw mode: bytes a cooked tty would eat or translate arrive as they are.
  const std::string bytes("\xfd\x09\x00\r\n\x03\x04\x11\x13\x7f", 10);
  ::write(cable.master, bytes.data(), bytes.size());
  EXPECT_EQ(read_text(*link), bytes);
  ASSERT_TRUE(write_text(*link, bytes));
  EXPECT_EQ(cable.receive(), bytes);
}

TEST(SerialLink, CablePulledClosesTheLinkAndItReopensWhenPutBack) {
  auto cable = std::make_unique<Cable>();
  auto link = make_link(ConnectionUrl::parse("serial://" + cable->path + ":57600"));
  ASSERT_TRUE(link->open()) << link->last_error();
  const std::string path = cable->path;
  cable.reset();  // pulled
  std::array<std::uint8_t, 64> buffer{};
  for (int i = 0; i < 20 * cover::test::whole_time_scale() && link->is_open(); ++i) {
    link->read(buffer.data(), buffer.size(), milliseconds(100));
  }
  EXPECT_FALSE(link->is_open());
  EXPECT_FALSE(link->last_error().empty());
  EXPECT_FALSE(write_text(*link, "x"));
  EXPECT_FALSE(link->open());
  EXPECT_NE(link->last_error().find("cannot open the device"), std::string::npos)
      << link->last_error();
  EXPECT_NE(link->last_error().find(path), std::string::npos) << link->last_error();

  Cable back;  // the same path, a new pty
  ASSERT_TRUE(link->open()) << link->last_error();
  ASSERT_TRUE(write_text(*link, "again"));
  EXPECT_EQ(back.receive(), "again");
}

TEST(SerialLink, NotATtyIsRefused) {
  const std::string path = test::scratch_path("plain-file");
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fclose(f);
  }
  auto link = make_link(ConnectionUrl::parse("serial://" + path + ":115200"));
  EXPECT_FALSE(link->open());
  EXPECT_NE(link->last_error().find("not a serial port"), std::string::npos) << link->last_error();
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cover::mavlink
