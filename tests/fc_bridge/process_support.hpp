#pragma once

#include <unistd.h>

#include <sys/socket.h>

#include <netinet/in.h>

#include <arpa/inet.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>

#include "cover/clock/clock.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"

// What the bridge's process tests share: deadlines scaled by COVER_TEST_TIME_SCALE, the
// bridge started on a domain, and an agent's command stream published over DDS.
namespace cover::fc_bridge::test {

using cover::test::scaled;
using cover::test::wait_until;

inline dds::ParticipantOptions on_domain(int domain) {
  dds::ParticipantOptions options;
  options.vendor = dds::Vendor::Cyclone;
  options.domain_id = domain;
  options.participant_name = "fc-bridge-test";
  return options;
}

// The `node` executable on $PATH (child processes are started by exec, without a PATH
// lookup); empty when Node is not installed.
inline std::string find_node() {
  const char* path = std::getenv("PATH");
  const std::string dirs = path != nullptr ? path : "";
  for (std::size_t at = 0; at <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', at), dirs.size());
    const std::filesystem::path candidate =
        std::filesystem::path(dirs.substr(at, end - at)) / "node";
    if (end > at && ::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    at = end + 1;
  }
  return "";
}

// A loopback UDP port free now, below Linux's ephemeral range (32768-60999): a port the
// kernel hands out for "any port" (a DDS participant's socket) cannot take it between this
// check and the bind of the process it is meant for.
inline int free_udp_port() {
  static std::mt19937 rng(static_cast<unsigned>(::getpid()) ^
                          static_cast<unsigned>(clock::monotonic_ns()));
  std::uniform_int_distribution<int> pick(20000, 32000);
  for (int attempt = 0; attempt < 200; ++attempt) {
    const int port = pick(rng);
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    const bool free = ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0;
    ::close(fd);
    if (free) return port;
  }
  throw std::runtime_error("no free UDP port on 127.0.0.1 in 20000-32000");
}

// cover-fc-bridge for UAV 0 on `domain`, its log in the test's scratch folder.
inline process::ChildProcess start_bridge(int domain, const std::vector<std::string>& args) {
  std::vector<std::string> argv{COVER_FC_BRIDGE,       "--id", "0", "--dds", "cyclone", "--domain",
                                std::to_string(domain)};
  argv.insert(argv.end(), args.begin(), args.end());
  process::SpawnOptions options;
  options.log_file = cover::test::scratch_path("fc_bridge.log");
  options.null_stdin = true;
  options.close_other_fds = true;  // a pty master of the test held by the bridge: no hang-up
  return process::ChildProcess(argv, options);
}

// The UAV agent's side: UavCommand samples on cover/uav/0/cmd at 100 Hz from a thread,
// stamped with the host's clock (the bridge runs --clock system), FLU rates (0.1, 0.2, 0.3)
// rad/s and 9.81 m/s^2: a hover.
class AgentStream {
 public:
  explicit AgentStream(dds::Participant& participant)
      : writer_(participant.make_writer(dds::topics::uav_command(0))), thread_([this] { run(); }) {}
  ~AgentStream() {
    stop_ = true;
    thread_.join();
  }
  std::uint32_t sent() const { return seq_; }

 private:
  void run() {
    while (!stop_) {
      msg::UavCommand c;
      c.uav_id = 0;
      c.stamp_ns = clock::system_ns();
      c.seq = ++seq_;
      c.thrust_m_s2 = 9.81;
      c.body_rates_rad_s.x = 0.1;
      c.body_rates_rad_s.y = 0.2;
      c.body_rates_rad_s.z = 0.3;
      c.armed = true;
      c.measurement_stamp_ns = c.stamp_ns;
      writer_.write(c);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));  // the agent's 100 Hz
    }
  }
  dds::Writer<msg::UavCommand> writer_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint32_t> seq_{0};
  std::thread thread_;
};

}  // namespace cover::fc_bridge::test
