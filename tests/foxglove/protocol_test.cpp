// The Foxglove protocol pieces (cover_foxglove): the client-message parser on good and bad
// input, the messageData frame layout, and the 3D scene's frame tree from relative states.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "cover/foxglove/foxglove_schemas.hpp"
#include "cover/foxglove/protocol.hpp"
#include "cover/foxglove/scene.hpp"

namespace cover::foxglove {
namespace {

using nlohmann::json;

TEST(FoxgloveProtocol, ParsesSubscribeAndUnsubscribe) {
  const auto s = parse_client_text(
      R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":7,"channelId":4}]})");
  ASSERT_EQ(s.op, ClientOp::Subscribe) << s.error;
  ASSERT_EQ(s.subscriptions.size(), 2u);
  EXPECT_EQ(s.subscriptions[1].id, 7u);
  EXPECT_EQ(s.subscriptions[1].channel_id, 4u);
  const auto u = parse_client_text(R"({"op":"unsubscribe","subscriptionIds":[0,7]})");
  ASSERT_EQ(u.op, ClientOp::Unsubscribe) << u.error;
  EXPECT_EQ(u.subscription_ids, (std::vector<std::uint32_t>{0, 7}));
}

TEST(FoxgloveProtocol, RefusesWhatIsNotAMessageOfTheProtocolSayingWhy) {
  for (const std::string& bad : std::vector<std::string>{
           "", "{not json", "[1,2]", R"({"op":3})", R"({"op":"launch"})",
           R"({"op":"subscribe","subscriptions":[]})",
           R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})",
           R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":1}]})",
           R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1},{"id":1,"channelId":2}]})",
           R"({"op":"unsubscribe","subscriptionIds":[1.5]})", std::string(100, '['),
           std::string(kMaxClientMessageBytes + 1, ' '), "{\"op\":\"\xff\"}"}) {
    const auto m = parse_client_text(bad);
    EXPECT_EQ(m.op, ClientOp::Invalid) << bad.substr(0, 80);
    EXPECT_FALSE(m.error.empty());
    EXPECT_TRUE(json::accept(status_json(StatusLevel::Error, m.error + "\xff"))) << m.error;
  }
  EXPECT_EQ(parse_client_text(R"({"op":"advertise","channels":[]})").op, ClientOp::Unsupported);
  EXPECT_EQ(parse_client_binary(std::string("\x01\x00\x00\x00\x00", 5)).op, ClientOp::Unsupported);
  EXPECT_EQ(parse_client_binary("\x07").op, ClientOp::Invalid);
  EXPECT_EQ(parse_client_binary("").op, ClientOp::Invalid);
}

TEST(FoxgloveProtocol, MessageDataFrameIsOpcodeSubscriptionTimeThenPayload) {
  const std::uint8_t payload[] = {0, 1, 0, 0, 42};
  std::string frame;
  message_data_frame(0x01020304, 0x1122334455667788ULL, payload, sizeof payload, frame);
  const std::string expected(
      "\x01\x04\x03\x02\x01\x88\x77\x66\x55\x44\x33\x22\x11\x00\x01\x00\x00\x2a", 18);
  EXPECT_EQ(frame, expected);
}

TEST(FoxgloveProtocol, AdvertiseCarriesTheSchemaOfEachChannel) {
  Channel c = json_channel("cover/foxglove/tf", kFrameTransformSchema);
  c.id = 5;
  const json a = json::parse(advertise_json({c}));
  EXPECT_EQ(a["op"], "advertise");
  EXPECT_EQ(a["channels"][0]["id"], 5);
  EXPECT_EQ(a["channels"][0]["schemaEncoding"], "jsonschema");
  const json schema = json::parse(a["channels"][0]["schema"].get<std::string>());
  EXPECT_EQ(schema["title"], "foxglove.FrameTransform");
  EXPECT_TRUE(schema["properties"].contains("child_frame_id"));
  EXPECT_TRUE(json::parse(scene_update_json_schema())["properties"].contains("entities"));
}

msg::RelativeState state(std::uint32_t u, std::uint32_t k, double x) {
  msg::RelativeState s;
  s.uav_id = u;
  s.ugv_id = k;
  s.valid = true;
  s.position_m = {x, 0, 0};
  s.attitude = {1, 0, 0, 0};
  return s;
}

TEST(FoxgloveScene, FramesFormASpanningForestOfFreshValidStates) {
  Scene scene(SceneOptions{2, 3, 0.5, 1.0});
  const std::int64_t t = 10'000'000'000;
  scene.on_relative_state(state(0, 0, 1), t);
  scene.on_relative_state(state(0, 1, 2), t);
  scene.on_relative_state(state(1, 1, 3), t);
  auto lost = state(1, 2, 4);
  lost.valid = false;
  scene.on_relative_state(lost, t);
  std::vector<std::pair<std::string, std::string>> edges;
  for (const auto& text : scene.frame_transforms(t)) {
    const json j = json::parse(text);
    edges.emplace_back(j["parent_frame_id"], j["child_frame_id"]);
  }
  // ugv_0 -> uav_0 -> ugv_1 -> uav_1; ugv_2 only by an invalid state: not placed.
  EXPECT_EQ(edges, (std::vector<std::pair<std::string, std::string>>{
                       {"ugv_0", "uav_0"}, {"uav_0", "ugv_1"}, {"ugv_1", "uav_1"}}));
  EXPECT_TRUE(scene.frame_transforms(t + 600'000'000).empty()) << "stale after 0.5 s";
  const json update = json::parse(scene.scene_update(t));
  EXPECT_EQ(update["entities"].size(), 4u);  // ugv_0, uav_0, ugv_1, uav_1
}

}  // namespace
}  // namespace cover::foxglove
