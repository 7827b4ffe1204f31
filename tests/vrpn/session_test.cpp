// The VRPN client session (services/vrpn) on bytes written by hand from the protocol.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cover/vrpn/client_session.hpp"
#include "spec_bytes.hpp"

namespace {

using namespace cover::test::vrpn_spec;
namespace vrpn = cover::vrpn;

// A test-side message writer, independent of the client's and the server's.
void put32(Bytes& b, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<std::uint8_t>(v >> s));
}
void put_double(Bytes& b, double d) {
  std::uint64_t bits;
  std::memcpy(&bits, &d, 8);
  put32(b, static_cast<std::uint32_t>(bits >> 32));
  put32(b, static_cast<std::uint32_t>(bits));
}
Bytes message(std::int32_t sender, std::int32_t type, const Bytes& payload, std::int32_t sec = 0,
              std::int32_t usec = 0) {
  Bytes b;
  put32(b, static_cast<std::uint32_t>(24 + payload.size()));
  put32(b, static_cast<std::uint32_t>(sec));
  put32(b, static_cast<std::uint32_t>(usec));
  put32(b, static_cast<std::uint32_t>(sender));
  put32(b, static_cast<std::uint32_t>(type));
  put32(b, 0);
  b.insert(b.end(), payload.begin(), payload.end());
  while (b.size() % 8 != 0) b.push_back(0);
  return b;
}
Bytes description(std::int32_t id, std::int32_t system_type, const std::string& name) {
  Bytes p;
  put32(p, static_cast<std::uint32_t>(name.size() + 1));
  p.insert(p.end(), name.begin(), name.end());
  p.push_back(0);
  return message(id, system_type, p);
}
Bytes pose_payload(const std::array<double, 7>& v, std::int32_t sensor = 0) {
  Bytes p;
  put32(p, static_cast<std::uint32_t>(sensor));
  put32(p, static_cast<std::uint32_t>(sensor));
  for (double d : v) put_double(p, d);
  return p;
}

struct Fed {
  std::vector<vrpn::TrackerReport> reports;
  bool ok = true;
};

Fed feed(vrpn::ClientSession& s, const Bytes& bytes, std::size_t chunk = 0) {
  Fed fed;
  const auto on = [&](const vrpn::TrackerReport& r) { fed.reports.push_back(r); };
  if (chunk == 0) chunk = bytes.size();
  for (std::size_t at = 0; at < bytes.size() && fed.ok; at += chunk) {
    fed.ok = s.feed(bytes.data() + at, std::min(chunk, bytes.size() - at), on);
  }
  return fed;
}

vrpn::ClientSession session(std::vector<std::string> bodies = {"UAV_A"}) {
  vrpn::SessionOptions o;
  o.bodies = std::move(bodies);
  vrpn::ClientSession s(o);
  s.start();
  return s;
}

TEST(VrpnSession, SendsTheCookieFirst) {
  auto s = session();
  ASSERT_EQ(s.outgoing_bytes(), 24u);
  EXPECT_EQ(Bytes(s.outgoing(), s.outgoing() + 24), cookie("07.38"));
}

TEST(VrpnSession, ReadsThePoseOfTheSpecExampleWholeAndByteByByte) {
  for (std::size_t chunk : {0, 1, 7}) {
    auto s = session();
    const Fed fed =
        feed(s, cat({cookie(), sender_uav_a_id0(), type_pos_quat_id5(), pos_quat_sender0_type5()}),
             chunk);
    ASSERT_TRUE(fed.ok);
    ASSERT_EQ(fed.reports.size(), 1u) << "chunk " << chunk;
    const auto& r = fed.reports[0];
    EXPECT_TRUE(r.valid);
    EXPECT_EQ(r.body, 0);
    EXPECT_EQ(r.kind, vrpn::TrackerReport::Kind::Pose);
    EXPECT_EQ(r.time.seconds, 1);
    EXPECT_EQ(r.time.microseconds, 500000);
    EXPECT_EQ(r.time.to_ns(), 1'500'000'000);
    EXPECT_EQ(r.position, (std::array<double, 3>{1.0, 2.0, -0.5}));
    EXPECT_NEAR(r.quaternion_xyzw[2], 0.6, 1e-15);
    EXPECT_NEAR(r.quaternion_xyzw[3], 0.8, 1e-15);
    EXPECT_EQ(s.stats().poses, 1u);
    EXPECT_EQ(s.stats().refused(), 0u);
  }
}

TEST(VrpnSession, OlderMinorVersionIsAcceptedAndCounted) {
  auto s = session();
  const Fed fed = feed(
      s, cat({cookie("07.35"), sender_uav_a_id0(), type_pos_quat_id5(), pos_quat_sender0_type5()}));
  EXPECT_TRUE(fed.ok);
  EXPECT_EQ(fed.reports.size(), 1u);
  EXPECT_TRUE(s.minor_version_mismatch());
  EXPECT_EQ(s.stats().minor_version_mismatches, 1u);
}

TEST(VrpnSession, ForeignCookieDropsTheConnection) {
  for (const Bytes& first : {cookie("08.00"), text("HTTP/1.1 200 OK\r\nContent-Length: 0\r\n")}) {
    auto s = session();
    EXPECT_FALSE(feed(s, first).ok);
    EXPECT_FALSE(s.handshake_done());
    EXPECT_EQ(s.stats().bad_cookies, 1u);
    EXPECT_FALSE(s.error().empty());
  }
}

TEST(VrpnSession, AfterTheCookieItDescribesItsSendersAndTypes) {
  auto s = session();
  s.consume_outgoing(24);
  feed(s, cookie());
  // First our sender 0, "UAV_A", exactly as the spec example writes the server's.
  const Bytes expected = sender_uav_a_id0();
  ASSERT_GE(s.outgoing_bytes(), expected.size());
  EXPECT_EQ(Bytes(s.outgoing(), s.outgoing() + expected.size()), expected);
}

TEST(VrpnSession, IdsAreMappedByNamePerConnection) {
  auto s = session({"Truck_2", "UAV_A"});
  const Bytes bytes = cat({cookie(), description(7, -1, "UAV_A"), description(3, -1, "Truck_2"),
                           description(9, -2, "vrpn_Tracker Pos_Quat"),
                           message(3, 9, pose_payload({5, 0, 0, 0, 0, 0, 1}), 2, 0),
                           message(7, 9, pose_payload({6, 0, 0, 0, 0, 0, 1}), 2, 0)});
  Fed fed = feed(s, bytes);
  ASSERT_EQ(fed.reports.size(), 2u);
  EXPECT_EQ(fed.reports[0].body, 0);  // Truck_2
  EXPECT_EQ(fed.reports[0].position[0], 5.0);
  EXPECT_EQ(fed.reports[1].body, 1);  // UAV_A
  // A new connection may number everything differently.
  s.start();
  fed = feed(s, cat({cookie(), description(1, -1, "Truck_2"), description(0, -1, "UAV_A"),
                     description(4, -2, "vrpn_Tracker Pos_Quat"),
                     message(1, 4, pose_payload({8, 0, 0, 0, 0, 0, 1}))}));
  ASSERT_EQ(fed.reports.size(), 1u);
  EXPECT_EQ(fed.reports[0].body, 0);
  EXPECT_EQ(fed.reports[0].position[0], 8.0);
}

TEST(VrpnSession, VelocityReportsAreRead) {
  auto s = session();
  Bytes payload = pose_payload({0.5, -1, 2, 0, 0, 0, 1});
  put_double(payload, 0.01);  // 72 bytes
  const Fed fed =
      feed(s, cat({cookie(), sender_uav_a_id0(), description(2, -2, "vrpn_Tracker Velocity"),
                   message(0, 2, payload)}));
  ASSERT_EQ(fed.reports.size(), 1u);
  EXPECT_EQ(fed.reports[0].kind, vrpn::TrackerReport::Kind::Velocity);
  EXPECT_EQ(fed.reports[0].position, (std::array<double, 3>{0.5, -1, 2}));
  EXPECT_EQ(s.stats().velocities, 1u);
}

TEST(VrpnSession, NanPosesAndZeroQuaternionsMarkTheBodyLost) {
  auto s = session();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Fed fed = feed(s, cat({cookie(), sender_uav_a_id0(), type_pos_quat_id5(),
                               message(0, 5, pose_payload({nan, nan, nan, nan, nan, nan, nan})),
                               message(0, 5, pose_payload({1, 2, 3, 0, 0, 0, 0})),
                               message(0, 5, pose_payload({1e300, 2, 3, 0, 0, 0, 1}))}));
  ASSERT_TRUE(fed.ok);
  ASSERT_EQ(fed.reports.size(), 3u);
  for (const auto& r : fed.reports) {
    EXPECT_FALSE(r.valid);
    EXPECT_EQ(r.position, (std::array<double, 3>{0, 0, 0}));
  }
  EXPECT_EQ(s.stats().lost_samples, 3u);
}

TEST(VrpnSession, WrongSizesUnknownIdsAndUntrackedBodiesAreCountedNotDelivered) {
  auto s = session();
  Bytes short_payload = pose_payload({1, 2, 3, 0, 0, 0, 1});
  short_payload.resize(56);
  const Fed fed =
      feed(s, cat({cookie(), sender_uav_a_id0(), type_pos_quat_id5(), description(4, -1, "Other"),
                   message(0, 5, short_payload), message(0, 77, pose_payload({})),
                   message(33, 5, pose_payload({0, 0, 0, 0, 0, 0, 1})),
                   message(4, 5, pose_payload({0, 0, 0, 0, 0, 0, 1})), pos_quat_sender0_type5()}));
  ASSERT_TRUE(fed.ok);
  ASSERT_EQ(fed.reports.size(), 1u);  // the well-formed one, after all the others
  EXPECT_EQ(s.stats().wrong_size, 1u);
  EXPECT_EQ(s.stats().unknown_type, 1u);
  EXPECT_EQ(s.stats().unknown_sender, 1u);
  EXPECT_EQ(s.stats().untracked, 1u);
}

TEST(VrpnSession, ALengthOutsideTheLimitsPutsTheStreamOutOfStep) {
  for (std::uint32_t bad : {0u, 16u, 23u, 4097u, 0x7fffffffu, 0xffffffffu}) {
    auto s = session();
    Bytes m = pos_quat_sender0_type5();
    m[0] = static_cast<std::uint8_t>(bad >> 24);
    m[1] = static_cast<std::uint8_t>(bad >> 16);
    m[2] = static_cast<std::uint8_t>(bad >> 8);
    m[3] = static_cast<std::uint8_t>(bad);
    const Fed fed = feed(
        s, cat({cookie(), sender_uav_a_id0(), type_pos_quat_id5(), m, pos_quat_sender0_type5()}));
    EXPECT_FALSE(fed.ok) << bad;
    EXPECT_TRUE(fed.reports.empty());
    EXPECT_EQ(s.stats().bad_lengths, 1u);
    EXPECT_NE(s.error().find(std::to_string(static_cast<std::int32_t>(bad))), std::string::npos)
        << s.error();
  }
}

TEST(VrpnSession, TheLengthExcludesThePaddingButThePaddingIsSkipped) {
  // A 26-byte payload (the Pos_Quat type description) is followed by 6 zero bytes; a
  // reader that trusted the length alone would read the next header 6 bytes early.
  auto s = session();
  const Fed fed =
      feed(s, cat({cookie(), type_pos_quat_id5(), sender_uav_a_id0(), pos_quat_sender0_type5()}));
  ASSERT_TRUE(fed.ok);
  EXPECT_EQ(fed.reports.size(), 1u);
}

TEST(VrpnSession, PingsAreAnsweredWithPongsOnOurSenderOfThatName) {
  auto s = session({"Truck_2", "UAV_A"});
  feed(s, cookie());
  s.consume_outgoing(s.outgoing_bytes());
  feed(s, cat({description(12, -1, "UAV_A"), description(6, -2, "vrpn_Base ping_message"),
               message(12, 6, {}, 10, 20)}));
  EXPECT_EQ(s.stats().pings_answered, 1u);
  // Our sender 1 is UAV_A, our type 3 the pong (described after the cookie).
  const Bytes pong = hex("00000018 0000000a 00000014 00000001 00000003 00000000");
  ASSERT_EQ(s.outgoing_bytes(), pong.size());
  EXPECT_EQ(Bytes(s.outgoing(), s.outgoing() + pong.size()), pong);
}

TEST(VrpnSession, MalformedDescriptionsAreRefused) {
  auto s = session();
  Bytes no_nul = description(0, -1, "UAV_A");
  no_nul[24 + 4 + 5] = 'X';  // the NUL
  Bytes long_length = description(0, -1, "UAV_A");
  long_length[24 + 3] = 60;
  const Fed fed =
      feed(s, cat({cookie(), no_nul, long_length, type_pos_quat_id5(), pos_quat_sender0_type5()}));
  EXPECT_TRUE(fed.ok);
  EXPECT_TRUE(fed.reports.empty());
  EXPECT_EQ(s.stats().bad_descriptions, 2u);
  EXPECT_EQ(s.stats().unknown_sender, 1u);
}

}  // namespace
