// cover-fc-bridge on a serial link: a pty pair is the cable, the test plays the autopilot
// on its master with our codec, publishes the agent's commands over DDS, pulls the cable
// (master closed, device path gone) and puts it back (a new pty behind the same path).
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>

#include "cover/dds/domain_claim.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/parser.hpp"
#include "cover/mavlink/protocol.hpp"
#include "process_support.hpp"

namespace cover::fc_bridge {
namespace {

namespace mav = cover::mavlink;
using namespace std::chrono_literals;
using test::wait_until;

constexpr std::uint8_t kSys = 7;

// The autopilot's end of a pty "cable" reached through a symlink in the scratch folder:
// HEARTBEAT at 1 Hz (PX4, disarmed, POSCTL), the bridge's SET_ATTITUDE_TARGETs recorded.
class PtyAutopilot {
 public:
  PtyAutopilot() : path_(cover::test::scratch_path("ttyACM-fc")), encoder_(kSys, 1) {
    plug();
    thread_ = std::thread([this] { run(); });
  }
  ~PtyAutopilot() {
    stop_ = true;
    thread_.join();
    pull();
  }
  const std::string& path() const { return path_; }

  void pull() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (master_ >= 0) ::close(master_);
    if (slave_ >= 0) ::close(slave_);
    master_ = slave_ = -1;
    std::filesystem::remove(path_);
  }
  void plug() {
    int master = -1;
    int slave = -1;
    ASSERT_EQ(::openpty(&master, &slave, nullptr, nullptr, nullptr), 0);
    termios tio{};
    ::tcgetattr(slave, &tio);
    ::cfmakeraw(&tio);  // no echo of our heartbeats before the bridge opens the port
    ::tcsetattr(slave, TCSANOW, &tio);
    std::filesystem::remove(path_);
    std::filesystem::create_symlink(::ttyname(slave), path_);
    std::lock_guard<std::mutex> lock(mutex_);
    master_ = master;
    slave_ = slave;
    parser_.reset();
  }
  std::size_t setpoints() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return setpoints_;
  }
  std::optional<mav::SetAttitudeTarget> last() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_;
  }
  std::uint64_t parser_errors() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return parser_.stats().errors();
  }

 private:
  void run() {
    auto next_heartbeat = std::chrono::steady_clock::now();
    while (!stop_) {
      if (std::chrono::steady_clock::now() >= next_heartbeat) {
        send_heartbeat();
        next_heartbeat += 1s;
      }
      receive();
    }
  }
  void send_heartbeat() {
    mav::Heartbeat hb;
    hb.type = mav::mav_type::kQuadrotor;
    hb.autopilot = mav::mav_autopilot::kPx4;
    hb.base_mode = mav::mav_mode_flag::kCustomModeEnabled;
    hb.custom_mode = mav::px4_mode::custom_mode(mav::px4_mode::kMainPosctl);
    hb.system_status = mav::mav_state::kStandby;
    std::lock_guard<std::mutex> lock(mutex_);
    if (master_ < 0) return;
    const mav::EncodedFrame frame = encoder_.encode(hb);
    if (::write(master_, frame.bytes.data(), frame.size) < 0) return;
  }
  void receive() {
    int fd = -1;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      fd = master_;
    }
    if (fd < 0) {
      std::this_thread::sleep_for(5ms);  // the cable is out: nothing to wait on
      return;
    }
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 5) <= 0 || (p.revents & POLLIN) == 0) return;
    std::array<std::uint8_t, 1024> buffer{};
    std::lock_guard<std::mutex> lock(mutex_);
    if (master_ != fd) return;  // pulled meanwhile
    const ssize_t n = ::read(fd, buffer.data(), buffer.size());
    if (n <= 0) return;
    parser_.feed(buffer.data(), static_cast<std::size_t>(n), [this](const mav::Frame& frame) {
      if (const auto sp = mav::decode<mav::SetAttitudeTarget>(frame)) {
        ++setpoints_;
        last_ = *sp;
      }
    });
  }

  std::string path_;
  mav::Encoder encoder_;
  mutable std::mutex mutex_;
  int master_ = -1;
  int slave_ = -1;
  mav::StreamParser parser_;
  std::size_t setpoints_ = 0;
  std::optional<mav::SetAttitudeTarget> last_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

TEST(FcBridgeProcess, SerialCablePulledAndPutBackWithoutARestart) {
  const auto claim = dds::DomainClaim::claim_any(200, 209);
  PtyAutopilot autopilot;
  auto bridge = test::start_bridge(
      claim.domain(), {"--autopilot", "px4", "--url", "serial://" + autopilot.path() + ":921600",
                       "--clock", "system"});
  dds::Participant participant(test::on_domain(claim.domain()));
  auto fc = participant.make_reader(dds::topics::fc_state(0));
  test::AgentStream agent(participant);
  auto fc_state = [&fc] { return fc.latest() ? std::optional(fc.latest()->sample) : std::nullopt; };

  ASSERT_TRUE(wait_until([&] { return fc_state() && fc_state()->link_ok; }, 15s))
      << "the bridge never reported the autopilot's link up";
  EXPECT_EQ(fc_state()->system_id, kSys);
  EXPECT_EQ(fc_state()->autopilot, msg::FcAutopilot::FC_AUTOPILOT_PX4);
  EXPECT_EQ(fc_state()->mode_name, "POSCTL");
  ASSERT_TRUE(wait_until([&] { return autopilot.setpoints() >= 50; }, 10s));
  const auto sp = *autopilot.last();
  EXPECT_EQ(sp.type_mask, 128);
  EXPECT_EQ(sp.target_system, kSys);
  EXPECT_EQ(sp.target_component, 1);
  EXPECT_FLOAT_EQ(sp.body_roll_rate, 0.1F);
  EXPECT_FLOAT_EQ(sp.body_pitch_rate, -0.2F);  // FLU -> FRD
  EXPECT_FLOAT_EQ(sp.body_yaw_rate, -0.3F);
  EXPECT_NEAR(sp.thrust, 0.4905F, 1e-4F);  // 9.81 m/s^2 at the shipped hover thrust
  EXPECT_FALSE(fc_state()->armed);         // never armed without an operator
  EXPECT_EQ(autopilot.parser_errors(), 0U);

  autopilot.pull();
  ASSERT_TRUE(wait_until([&] { return fc_state() && !fc_state()->link_ok; }, 5s))
      << "the bridge did not report the link lost";
  const std::size_t before = autopilot.setpoints();

  autopilot.plug();
  ASSERT_TRUE(wait_until([&] { return fc_state() && fc_state()->link_ok; }, 10s))
      << "the bridge did not come back on the new pty";
  ASSERT_TRUE(wait_until([&] { return autopilot.setpoints() >= before + 50; }, 10s))
      << "setpoints did not flow again after the cable was put back";
  EXPECT_FLOAT_EQ(autopilot.last()->body_pitch_rate, -0.2F);
  EXPECT_EQ(bridge.terminate(), 0);
}

}  // namespace
}  // namespace cover::fc_bridge
