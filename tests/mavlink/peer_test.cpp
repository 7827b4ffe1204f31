// The codec against an independent implementation, node-mavlink 2.3.0 (peer/): frames it
// writes decode here to exactly its values (layout and CRC_EXTRA of every message, signing),
// frames we write decode there to exactly ours, and the fake autopilot the bridge's tests
// fly against keeps its contract. Skips only when Node is absent.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "cover/mavlink/connection_url.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/hil_messages.hpp"
#include "cover/mavlink/link.hpp"
#include "cover/mavlink/parser.hpp"
#include "cover/mavlink/protocol.hpp"
#include "cover/mavlink/tcp_server_link.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "message_json.hpp"
#include "sample_messages.hpp"
#include "stream_builder.hpp"

namespace cover::mavlink {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using test::Bytes;

std::string find_node() {
  const char* path = std::getenv("PATH");
  std::string dirs = path != nullptr ? path : "";
  for (std::size_t at = 0; at <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', at), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(at, end - at)) / "node";
    if (!candidate.parent_path().empty() && ::access(candidate.c_str(), X_OK) == 0) {
      return candidate.string();
    }
    at = end + 1;
  }
  return "";
}

const fs::path kPeerDir = COVER_MAVLINK_PEER_DIR;

// Node and the pinned node-mavlink, or the reason the test cannot run: no Node skips
// (a machine without it), Node without the peer installed fails (scripts/setup installs it).
class MavlinkPeer : public ::testing::Test {
 protected:
  void SetUp() override {
    node_ = find_node();
    if (node_.empty())
      GTEST_SKIP() << "node is not installed: the node-mavlink peer tests need Node >= 18";
    ASSERT_TRUE(fs::exists(kPeerDir / "node_modules" / "node-mavlink" / "package.json"))
        << "node-mavlink is not installed in " << kPeerDir
        << ": run scripts/setup (npm ci --prefix tests/mavlink/peer)";
  }

  // Runs a peer script to its end; its stdout (when captured) line by line.
  std::vector<std::string> run_script(const std::vector<std::string>& args, int timeout_s) {
    std::vector<std::string> argv{node_};
    argv.insert(argv.end(), args.begin(), args.end());
    process::SpawnOptions options;
    options.capture_stdout = true;
    options.null_stdin = true;
    process::ChildProcess child(argv, options);
    std::vector<std::string> lines;
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::seconds(timeout_s * cover::test::whole_time_scale());
    while (std::chrono::steady_clock::now() < deadline) {
      const auto line = child.read_line(milliseconds(200));
      if (line) {
        lines.push_back(*line);
      } else if (child.wait(milliseconds(0))) {
        break;
      }
    }
    const auto code = child.wait(milliseconds(0));
    EXPECT_TRUE(code.has_value()) << args[0] << " did not finish in " << timeout_s << " s";
    if (code) {
      EXPECT_EQ(*code, 0) << args[0] << " failed";
    }
    if (!code) child.terminate();
    return lines;
  }

  std::string node_;
};

Bytes read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

struct Parsed {
  std::vector<Frame> frames;
  ParserStats stats;
};

Parsed parse(const Bytes& stream, const ParserOptions& options) {
  Parsed out;
  StreamParser parser(options);
  parser.feed(stream.data(), stream.size(), [&out](const Frame& f) { out.frames.push_back(f); });
  out.stats = parser.stats();
  return out;
}

TEST_F(MavlinkPeer, ParsesNodeFramesToExactlyItsValues) {
  const std::string frames_path = cover::test::scratch_path("node_frames.bin");
  const std::string values_path = cover::test::scratch_path("node_frames.json");
  run_script(
      {(kPeerDir / "write_frames.js").string(), "--frames", frames_path, "--values", values_path},
      60);
  const Bytes stream = read_file(frames_path);
  const nlohmann::json expected = read_json(values_path);
  ASSERT_GE(expected.size(), 34U);  // 17 messages, unsigned and signed, and some v1

  ParserOptions options;
  options.signing_key = test::test_key();
  const Parsed p = parse(stream, options);
  EXPECT_EQ(p.stats.errors(), 0U);
  EXPECT_EQ(p.stats.unknown_ids, 0U);
  EXPECT_EQ(p.stats.garbage_bytes, 0U);
  ASSERT_EQ(p.frames.size(), expected.size());
  std::size_t signed_frames = 0;
  for (std::size_t i = 0; i < p.frames.size(); ++i) {
    const Frame& f = p.frames[i];
    const nlohmann::json& e = expected[i];
    SCOPED_TRACE("frame " + std::to_string(i) + ": " + e.dump());
    EXPECT_EQ(f.message_id, e["id"].get<std::uint32_t>());
    EXPECT_EQ(f.version, e["version"].get<int>());
    EXPECT_EQ(f.is_signed(), e["signed"].get<bool>());
    EXPECT_EQ(f.seq, e["seq"].get<int>());
    EXPECT_EQ(f.system_id, e["sysid"].get<int>());
    EXPECT_EQ(f.component_id, e["compid"].get<int>());
    EXPECT_EQ(f.payload_length, e["payload_length"].get<int>());
    const nlohmann::json ours = test::frame_to_json(f);
    EXPECT_EQ(ours["message"], e["message"]);
    EXPECT_EQ(ours["fields"], e["fields"]);
    signed_frames += f.is_signed() ? 1 : 0;
  }
  EXPECT_EQ(signed_frames, 17U);

  // The same bytes with a wrong key: exactly the signed frames refused.
  options.signing_key->secret[0] ^= 0x80;
  const Parsed wrong = parse(stream, options);
  EXPECT_EQ(wrong.stats.signature_errors, signed_frames);
  EXPECT_EQ(wrong.frames.size(), expected.size() - signed_frames);
  // The right key, signing required: exactly the unsigned ones refused.
  options.signing_key = test::test_key();
  options.require_signed = true;
  const Parsed required = parse(stream, options);
  EXPECT_EQ(required.stats.unsigned_refused, expected.size() - signed_frames);
  EXPECT_EQ(required.frames.size(), signed_frames);
}

// What we encode for node to read: each message unsigned then signed, plus all-zero
// messages (trimmed to one byte).
struct Sent {
  nlohmann::json message;
  bool is_signed = false;
  std::uint8_t sysid = 0;
  std::uint8_t compid = 0;
  std::size_t payload_length = 0;
};

template <typename M>
void encode_into(Bytes& stream, std::vector<Sent>& sent, Encoder& encoder, const M& message,
                 const char* name) {
  const EncodedFrame frame = encoder.encode(message);
  test::append(stream, test::bytes_of(frame));
  sent.push_back({{{"message", name}, {"fields", test::to_json(message)}},
                  (frame.bytes[2] & kIncompatSigned) != 0,
                  encoder.system_id(),
                  encoder.component_id(),
                  frame.bytes[1]});
}

TEST_F(MavlinkPeer, NodeReadsOurFramesToExactlyOurValues) {
  Encoder plain(1, 191);
  Encoder signer(42, 191, test::test_key(3));
  Bytes stream;
  std::vector<Sent> sent;
  const auto messages = test::sample_messages();
  for (Encoder* encoder : {&plain, &signer}) {
    std::apply(
        [&](const auto&... m) {
          const char* names[] = {"HEARTBEAT",
                                 "SYS_STATUS",
                                 "SCALED_IMU",
                                 "ATTITUDE_QUATERNION",
                                 "COMMAND_LONG",
                                 "COMMAND_ACK",
                                 "SET_ATTITUDE_TARGET",
                                 "ATTITUDE_TARGET",
                                 "HIGHRES_IMU",
                                 "TIMESYNC",
                                 "BATTERY_STATUS",
                                 "EXTENDED_SYS_STATE",
                                 "STATUSTEXT",
                                 "HIL_SENSOR",
                                 "HIL_ACTUATOR_CONTROLS",
                                 "HIL_STATE_QUATERNION",
                                 "HIL_GPS"};
          std::size_t i = 0;
          (encode_into(stream, sent, *encoder, m, names[i++]), ...);
        },
        messages);
  }
  encode_into(stream, sent, plain, ExtendedSysState{}, "EXTENDED_SYS_STATE");
  encode_into(stream, sent, plain, CommandAck{}, "COMMAND_ACK");

  const std::string frames_path = cover::test::scratch_path("our_frames.bin");
  {
    std::ofstream out(frames_path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(stream.data()), static_cast<long>(stream.size()));
  }
  const std::vector<std::string> lines =
      run_script({(kPeerDir / "read_frames.js").string(), "--frames", frames_path}, 60);
  ASSERT_EQ(lines.size(), 1U);
  const nlohmann::json read = nlohmann::json::parse(lines[0]);
  EXPECT_EQ(read["crc_errors"], 0);
  EXPECT_EQ(read["unknown"], 0);
  const nlohmann::json& frames = read["frames"];
  ASSERT_EQ(frames.size(), sent.size());
  for (std::size_t i = 0; i < sent.size(); ++i) {
    const nlohmann::json& f = frames[i];
    SCOPED_TRACE("frame " + std::to_string(i) + ": " + f.dump());
    EXPECT_EQ(f["message"], sent[i].message["message"]);
    EXPECT_EQ(f["fields"], sent[i].message["fields"]);
    EXPECT_EQ(f["version"], 2);
    EXPECT_EQ(f["signed"], sent[i].is_signed);
    if (sent[i].is_signed) {
      EXPECT_EQ(f["signature_valid"], true);
    }
    EXPECT_EQ(f["sysid"], sent[i].sysid);
    EXPECT_EQ(f["compid"], sent[i].compid);
    EXPECT_EQ(f["payload_length"], sent[i].payload_length);
  }
}

// A loopback UDP socket speaking to the fake autopilot with our codec.
class UdpPeer {
 public:
  UdpPeer() : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {}
  ~UdpPeer() { ::close(fd_); }
  UdpPeer(const UdpPeer&) = delete;
  UdpPeer& operator=(const UdpPeer&) = delete;

  void send(std::uint16_t port, const EncodedFrame& frame) {
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    to.sin_port = htons(port);
    ::sendto(fd_, frame.bytes.data(), frame.size, 0, reinterpret_cast<sockaddr*>(&to), sizeof(to));
  }
  // Reads what arrived (waiting up to `timeout`) into `parser`.
  void receive(StreamParser& parser, milliseconds timeout, const StreamParser::FrameHandler& on) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return;
    std::array<std::uint8_t, 2048> buffer{};
    const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), MSG_DONTWAIT);
    if (n > 0) parser.feed(buffer.data(), static_cast<std::size_t>(n), on);
  }

 private:
  int fd_;
};

// A free UDP port on loopback (the kernel's pick; released for the autopilot to bind).
std::uint16_t free_udp_port() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address));
  socklen_t length = sizeof(address);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
  ::close(fd);
  return ntohs(address.sin_port);
}

// One fake autopilot process and our side of its link, as the bridge would hold it.
class AutopilotSession {
 public:
  AutopilotSession(const std::string& node, const std::string& autopilot, std::uint8_t sysid,
                   const std::vector<std::string>& extra_args)
      : sysid_(sysid), port_(free_udp_port()), encoder_(sysid, mav_comp::kOnboardComputer) {
    std::vector<std::string> argv{node,          (kPeerDir / "fake_autopilot.js").string(),
                                  "--port",      std::to_string(port_),
                                  "--autopilot", autopilot,
                                  "--sysid",     std::to_string(sysid)};
    argv.insert(argv.end(), extra_args.begin(), extra_args.end());
    process::SpawnOptions spawn;
    spawn.capture_stdout = true;
    spawn.null_stdin = true;
    process_ = std::make_unique<process::ChildProcess>(argv, spawn);
  }

  template <typename M>
  void send(const M& message) {
    link_.send(port_, encoder_.encode(message));
  }
  void command(std::uint16_t id, float param1, float param2) {
    CommandLong c;
    c.command = id;
    c.param[0] = param1;
    c.param[1] = param2;
    c.target_system = sysid_;
    c.target_component = mav_comp::kAutopilot1;
    send(c);
  }

  // Receives until `done` or the (scaled) timeout, calling `each` between reads.
  bool until(
      const std::function<bool()>& done, double timeout_s,
      const std::function<void()>& each = [] {}) {
    const auto deadline =
        std::chrono::steady_clock::now() +
        milliseconds(static_cast<long>(timeout_s * 1000 * cover::test::whole_time_scale()));
    while (!done() && std::chrono::steady_clock::now() < deadline) {
      each();
      link_.receive(parser_, milliseconds(20), [this](const Frame& f) { received_.push_back(f); });
    }
    return done();
  }
  // Says hello until the autopilot's heartbeat comes back (it answers whoever spoke).
  bool connect() {
    Heartbeat hello;
    hello.type = mav_type::kOnboardController;
    hello.autopilot = mav_autopilot::kInvalid;
    return until([this] { return last<Heartbeat>().has_value(); }, 20, [&] { send(hello); });
  }
  std::optional<CommandAck> ack(std::uint16_t command) const {
    for (const Frame& f : received_) {
      const auto a = decode<CommandAck>(f);
      if (a && a->command == command) return a;
    }
    return std::nullopt;
  }
  // Sends a command and waits for its ACK, streaming `each` meanwhile.
  std::optional<CommandAck> command_acked(
      std::uint16_t id, float param1, float param2, const std::function<void()>& each = [] {}) {
    received_.clear();
    command(id, param1, param2);
    until([&] { return ack(id).has_value(); }, 10, each);
    return ack(id);
  }
  template <typename M>
  std::optional<M> last() const {
    for (auto it = received_.rbegin(); it != received_.rend(); ++it) {
      if (auto m = decode<M>(*it)) return m;
    }
    return std::nullopt;
  }
  // Stops it (SIGTERM, or its own end) and returns its one-line JSON summary.
  nlohmann::json summary(bool terminate) {
    if (terminate) ::kill(process_->pid(), SIGTERM);
    std::optional<std::string> line;
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::seconds(20 * cover::test::whole_time_scale());
    while (!line && std::chrono::steady_clock::now() < deadline) {
      line = process_->read_line(milliseconds(200));
    }
    EXPECT_TRUE(line.has_value()) << "no summary";
    EXPECT_EQ(process_->wait(std::chrono::seconds(10 * cover::test::whole_time_scale())), 0);
    return line ? nlohmann::json::parse(*line) : nlohmann::json();
  }

  std::vector<Frame>& received() { return received_; }
  const ParserStats& stats() const { return parser_.stats(); }

 private:
  std::uint8_t sysid_;
  std::uint16_t port_;
  std::unique_ptr<process::ChildProcess> process_;
  UdpPeer link_;
  StreamParser parser_;
  Encoder encoder_;
  std::vector<Frame> received_;
};

// The PX4 contract: OFFBOARD refused before the stream, accepted after 1.5 s of 50 Hz
// setpoints, arming on request, every frame checked, the summary printed on SIGTERM.
TEST_F(MavlinkPeer, FakeAutopilotKeepsItsPx4Contract) {
  constexpr std::uint8_t kSysid = 7;
  AutopilotSession px4(node_, "px4", kSysid, {"--duration-s", "60"});
  ASSERT_TRUE(px4.connect());
  EXPECT_EQ(px4.last<Heartbeat>()->autopilot, mav_autopilot::kPx4);
  const auto refused = px4.command_acked(mav_cmd::kDoSetMode, 1, px4_mode::kMainOffboard);
  ASSERT_TRUE(refused.has_value());
  EXPECT_EQ(refused->result, mav_result::kTemporarilyRejected);

  SetAttitudeTarget setpoint;
  setpoint.target_system = kSysid;
  setpoint.target_component = mav_comp::kAutopilot1;
  setpoint.type_mask = attitude_target_typemask::kIgnoreAttitude;
  setpoint.thrust = 0.4F;
  setpoint.body_roll_rate = 0.5F;
  auto last_send = std::chrono::steady_clock::now() - milliseconds(100);
  const auto stream = [&] {
    if (std::chrono::steady_clock::now() - last_send >= milliseconds(20)) {
      px4.send(setpoint);
      last_send = std::chrono::steady_clock::now();
    }
  };
  const auto started = std::chrono::steady_clock::now();
  px4.until([&] { return std::chrono::steady_clock::now() - started >= milliseconds(1500); }, 10,
            stream);
  const auto accepted = px4.command_acked(mav_cmd::kDoSetMode, 1, px4_mode::kMainOffboard, stream);
  ASSERT_TRUE(accepted.has_value());
  EXPECT_EQ(accepted->result, mav_result::kAccepted);
  const auto armed = px4.command_acked(mav_cmd::kComponentArmDisarm, 1, 0, stream);
  ASSERT_TRUE(armed.has_value());
  EXPECT_EQ(armed->result, mav_result::kAccepted);
  EXPECT_EQ(armed->target_system, kSysid);
  EXPECT_EQ(armed->target_component, mav_comp::kOnboardComputer);
  px4.received().clear();
  ASSERT_TRUE(px4.until(
      [&] {
        const auto hb = px4.last<Heartbeat>();
        return hb && (hb->base_mode & mav_mode_flag::kSafetyArmed) != 0;
      },
      10, stream));
  EXPECT_EQ(px4_mode::main_mode(px4.last<Heartbeat>()->custom_mode), px4_mode::kMainOffboard);
  EXPECT_EQ(px4.received().back().system_id, kSysid);
  EXPECT_EQ(px4.received().back().component_id, mav_comp::kAutopilot1);
  EXPECT_EQ(px4.stats().errors(), 0U);

  // A bad setpoint, then a command whose ACK proves it was read; then SIGTERM.
  SetAttitudeTarget bad = setpoint;
  bad.type_mask = 0;
  px4.send(bad);
  const auto unsupported = px4.command_acked(999, 0, 0);
  ASSERT_TRUE(unsupported.has_value());
  EXPECT_EQ(unsupported->result, mav_result::kUnsupported);
  const nlohmann::json summary = px4.summary(true);
  EXPECT_GE(summary["setpoints"].get<int>(), 50);
  EXPECT_GT(summary["setpoint_rate_hz"].get<double>(), 20.0);
  EXPECT_EQ(summary["bad_frame_count"], 1) << summary.dump();
  EXPECT_EQ(summary["crc_errors"], 0);
  EXPECT_EQ(summary["first_setpoint_before_offboard"], false);  // OFFBOARD was asked first
  EXPECT_EQ(summary["armed"], true);
  EXPECT_EQ(summary["mode_name"], "OFFBOARD");
  ASSERT_EQ(summary["commands"].size(), 4U);
  EXPECT_EQ(summary["commands"][0]["result"], mav_result::kTemporarilyRejected);
  EXPECT_EQ(summary["commands"][1]["result"], mav_result::kAccepted);
  EXPECT_EQ(summary["commands"][2]["command"], mav_cmd::kComponentArmDisarm);
  EXPECT_NEAR(summary["last_setpoint"]["thrust"].get<double>(), 0.4, 1e-6);
}

// The ArduPilot contract: GUIDED_NOGPS denied without a stream, landing disarms after
// --land-s, silence after --no-heartbeat-after-s, and its own end after --duration-s.
TEST_F(MavlinkPeer, FakeAutopilotKeepsItsArdupilotContract) {
  constexpr std::uint8_t kSysid = 3;
  AutopilotSession copter(node_, "ardupilot", kSysid,
                          {"--duration-s", "6", "--land-s", "0.3", "--no-heartbeat-after-s", "3"});
  ASSERT_TRUE(copter.connect());
  EXPECT_EQ(copter.last<Heartbeat>()->autopilot, mav_autopilot::kArdupilotMega);
  EXPECT_EQ(copter.last<Heartbeat>()->custom_mode, copter_mode::kStabilize);
  const auto denied = copter.command_acked(mav_cmd::kDoSetMode, 1, copter_mode::kGuidedNoGps);
  ASSERT_TRUE(denied.has_value());
  EXPECT_EQ(denied->result, mav_result::kDenied);
  EXPECT_EQ(copter.command_acked(mav_cmd::kComponentArmDisarm, 1, 0)->result,
            mav_result::kAccepted);
  EXPECT_EQ(copter.command_acked(mav_cmd::kNavLand, 0, 0)->result, mav_result::kAccepted);
  copter.received().clear();
  ASSERT_TRUE(copter.until(
      [&] {
        const auto hb = copter.last<Heartbeat>();
        return hb && hb->custom_mode == copter_mode::kLand &&
               (hb->base_mode & mav_mode_flag::kSafetyArmed) == 0;
      },
      5));
  // Silent from 3 s on: nothing arrives in the last second before its end at 6 s.
  copter.until([] { return false; }, 4.0);
  copter.received().clear();
  copter.until([] { return false; }, 1.0);
  EXPECT_TRUE(copter.received().empty()) << copter.received().size() << " frames after silence";
  const nlohmann::json summary = copter.summary(false);
  EXPECT_EQ(summary["autopilot"], "ardupilot");
  EXPECT_EQ(summary["setpoints"], 0);
  EXPECT_EQ(summary["armed"], false);
  EXPECT_EQ(summary["mode_name"], "LAND");
  ASSERT_EQ(summary["commands"].size(), 3U);
  EXPECT_EQ(summary["commands"][0]["result"], mav_result::kDenied);
}

// The tcpin:// server against a PX4-like simulator_mavlink client on node's net (peer/
// hil_client.js): it connects, says HEARTBEAT, answers each HIL_SENSOR with a
// HIL_ACTUATOR_CONTROLS of the same time, drops the connection once our next sensor frame
// shows we read its last answer and connects again, the later connections beginning with
// 300 bytes of garbage. The server serves each new
// connection, decodes every answer node-mavlink wrote, and node decodes every sensor frame
// to exactly our values.
TEST_F(MavlinkPeer, TcpServerServesAReconnectingHilClientThroughGarbage) {
  constexpr int kConnections = 3;
  constexpr int kAnswers = 4;
  const auto link = make_tcp_server_link("127.0.0.1", 0);
  ASSERT_TRUE(link->open()) << link->last_error();
  ASSERT_GT(link->local_port(), 0);
  EXPECT_FALSE(link->has_client());
  Encoder encoder(1, 51);
  const std::uint8_t probe[1] = {0};
  EXPECT_FALSE(link->write(probe, 1));  // no client yet

  process::SpawnOptions spawn;
  spawn.capture_stdout = true;
  spawn.null_stdin = true;
  process::ChildProcess client(
      {node_, (kPeerDir / "hil_client.js").string(), "--port", std::to_string(link->local_port()),
       "--connections", std::to_string(kConnections), "--answers", std::to_string(kAnswers),
       "--garbage"},
      spawn);

  StreamParser parser;
  std::uint64_t clients = 0;
  std::uint64_t time_usec = 1000;
  std::map<std::string, nlohmann::json> sent;  // time_usec -> the sensor frame's fields
  std::vector<std::pair<std::uint64_t, HilActuatorControls>> answers;  // connection, answer
  int heartbeats = 0;
  int answer_time_mismatches = 0;
  const auto send_sensor = [&] {
    HilSensor sensor;
    sensor.time_usec = time_usec;
    sensor.zacc = -9.80665F;
    sensor.xgyro = 0.001F * static_cast<float>(time_usec % 7);
    sensor.abs_pressure = 955.5F;
    sensor.fields_updated = hil_sensor_fields::kImu | hil_sensor_fields::kBaro;
    const EncodedFrame frame = encoder.encode(sensor);
    if (link->write(frame.bytes.data(), frame.size)) {
      sent[std::to_string(time_usec)] = test::to_json(sensor);
    }
  };
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::seconds(30 * cover::test::whole_time_scale());
  std::array<std::uint8_t, 4096> buffer{};
  while (answers.size() < static_cast<std::size_t>(kConnections * kAnswers) &&
         std::chrono::steady_clock::now() < deadline) {
    const std::size_t n = link->read(buffer.data(), buffer.size(), milliseconds(20));
    if (link->clients_accepted() != clients) {
      clients = link->clients_accepted();
      parser.reset();
      send_sensor();  // PX4 waits for sensors before it sends any actuator frame
    }
    parser.feed(buffer.data(), n, [&](const Frame& f) {
      if (decode<Heartbeat>(f)) ++heartbeats;
      if (const auto answer = decode<HilActuatorControls>(f)) {
        answer_time_mismatches += answer->time_usec == time_usec ? 0 : 1;
        answers.emplace_back(clients, *answer);
        time_usec += 4000;
        send_sensor();
      }
    });
  }
  ASSERT_EQ(answers.size(), static_cast<std::size_t>(kConnections * kAnswers));
  EXPECT_EQ(clients, static_cast<std::uint64_t>(kConnections));
  EXPECT_EQ(heartbeats, kConnections);
  EXPECT_EQ(answer_time_mismatches, 0);
  EXPECT_GT(parser.stats().garbage_bytes + parser.stats().refusals(), 0U);
  for (std::size_t i = 0; i < answers.size(); ++i) {
    const auto& [connection, answer] = answers[i];
    SCOPED_TRACE("answer " + std::to_string(i));
    EXPECT_EQ(connection, i / kAnswers + 1);
    EXPECT_EQ(answer.flags, kHilActuatorControlsLockstep);
    EXPECT_EQ(answer.mode, 129);
    const float first = connection == 1 ? 1.0F / 16.0F : 16.0F / 16.0F;
    EXPECT_EQ(answer.controls[0], first);
  }

  std::vector<nlohmann::json> lines;
  const auto line_deadline =
      std::chrono::steady_clock::now() + std::chrono::seconds(20 * cover::test::whole_time_scale());
  while (std::chrono::steady_clock::now() < line_deadline) {
    // Keep serving: the last connection's frames are read while node prints.
    link->read(buffer.data(), buffer.size(), milliseconds(10));
    const auto line = client.read_line(milliseconds(10));
    if (line) {
      lines.push_back(nlohmann::json::parse(*line));
      if (lines.back().contains("done")) break;
    }
  }
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.back()["done"], true);
  EXPECT_EQ(lines.back()["crc_errors"], 0);
  ASSERT_EQ(lines.size(), static_cast<std::size_t>(kConnections * kAnswers + 1));
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
    const nlohmann::json& fields = lines[i]["fields"];
    const auto it = sent.find(fields["time_usec"].get<std::string>());
    ASSERT_NE(it, sent.end()) << lines[i].dump();
    EXPECT_EQ(fields, it->second);
  }
  EXPECT_EQ(client.wait(std::chrono::seconds(10 * cover::test::whole_time_scale())), 0);
}

// tcp:// (client) against tcpin:// (server): bytes both ways, a dropped client noticed by
// the server (it accepts the reconnection), the client's reopen after the server went.
TEST(MavlinkTcp, ClientAndServerExchangeAndReconnect) {
  const auto server = make_tcp_server_link("127.0.0.1", 0);
  ASSERT_TRUE(server->open()) << server->last_error();
  const auto url = ConnectionUrl::parse("tcp://127.0.0.1:" + std::to_string(server->local_port()));
  EXPECT_EQ(url.to_string(), "tcp://127.0.0.1:" + std::to_string(server->local_port()));
  const auto client = make_link(url);
  ASSERT_TRUE(client->open()) << client->last_error();
  std::array<std::uint8_t, 64> buffer{};
  const std::uint8_t hello[3] = {1, 2, 3};
  ASSERT_TRUE(client->write(hello, sizeof hello));
  std::size_t got = 0;
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::seconds(5 * cover::test::whole_time_scale());
  while (got < sizeof hello && std::chrono::steady_clock::now() < deadline) {
    got += server->read(buffer.data() + got, buffer.size() - got, milliseconds(50));
  }
  ASSERT_EQ(got, sizeof hello);
  EXPECT_EQ(buffer[2], 3);
  EXPECT_TRUE(server->has_client());
  const std::uint8_t back[2] = {9, 8};
  ASSERT_TRUE(server->write(back, sizeof back));
  got = 0;
  while (got < sizeof back && std::chrono::steady_clock::now() < deadline) {
    got += client->read(buffer.data() + got, buffer.size() - got, milliseconds(50));
  }
  EXPECT_EQ(got, sizeof back);

  client->close();  // the server sees the hang-up on its next read
  while (server->has_client() && std::chrono::steady_clock::now() < deadline) {
    server->read(buffer.data(), buffer.size(), milliseconds(50));
  }
  EXPECT_FALSE(server->has_client());
  EXPECT_NE(server->last_error().find("closed"), std::string::npos) << server->last_error();
  ASSERT_TRUE(client->open());
  while (server->clients_accepted() < 2 && std::chrono::steady_clock::now() < deadline) {
    server->read(buffer.data(), buffer.size(), milliseconds(50));
  }
  EXPECT_EQ(server->clients_accepted(), 2U);

  server->close();
  while (client->is_open() && std::chrono::steady_clock::now() < deadline) {
    client->read(buffer.data(), buffer.size(), milliseconds(50));
  }
  EXPECT_FALSE(client->is_open());
  EXPECT_FALSE(client->write(hello, sizeof hello));
  EXPECT_FALSE(client->open());  // nobody listens any more
}

}  // namespace
}  // namespace cover::mavlink
