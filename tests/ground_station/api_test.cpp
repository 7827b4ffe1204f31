// The page's API parser and the access rules (ground_station/core), in one process.
#include <gtest/gtest.h>

#include <string>

#include "cover/ground_station/access.hpp"
#include "cover/ground_station/api.hpp"

namespace gs = cover::ground_station;

namespace {

const char* kTask =
    R"({"op":"submit","id":"r1","task":{"task_id":"t1","uav_id":0,"processes":[{"from_ugv":0,"to_ugv":1,)"
    R"("initial_point_m":[0,0,1.1],"transition_point_m":[0,0,1.1],"final_point_m":[0.1,0,0.25],)"
    R"("final_action":"deliver","vmax_m_s":%VMAX%,"amax_m_s2":2.0}]}})";

std::string task_with_vmax(const std::string& vmax) {
  std::string text = kTask;
  text.replace(text.find("%VMAX%"), 6, vmax);
  return text;
}

}  // namespace

TEST(GroundStationApi, ParsesEachOp) {
  const auto submit = gs::parse_request(task_with_vmax("1.0"), 2);
  ASSERT_EQ(submit.op, gs::ApiOp::Submit) << submit.error;
  EXPECT_EQ(submit.id, "r1");
  EXPECT_EQ(submit.task.task_id, "t1");
  ASSERT_EQ(submit.task.processes.size(), 1u);

  const auto abort = gs::parse_request(R"({"op":"abort","task_id":"t1"})", 2);
  ASSERT_EQ(abort.op, gs::ApiOp::Abort);
  EXPECT_EQ(abort.task_id, "t1");
  EXPECT_FALSE(abort.reason.empty());

  const auto fc = gs::parse_request(R"({"op":"fc","uav_id":3,"command":"land"})", 2);
  ASSERT_EQ(fc.op, gs::ApiOp::Fc);
  EXPECT_EQ(fc.uav_id, 3u);
  EXPECT_EQ(fc.fc, gs::FcCommand::Land);

  const auto record = gs::parse_request(R"({"op":"record","action":"stop"})", 2);
  ASSERT_EQ(record.op, gs::ApiOp::Record);
  EXPECT_FALSE(record.record_start);
}

TEST(GroundStationApi, TaskErrorsNameTheirField) {
  const auto slow = gs::parse_request(task_with_vmax("-1"), 2);
  ASSERT_EQ(slow.op, gs::ApiOp::Invalid);
  EXPECT_EQ(slow.field, "vmax_m_s") << slow.error;
  EXPECT_EQ(slow.id, "r1");

  std::string bad_ugv = task_with_vmax("1.0");
  bad_ugv.replace(bad_ugv.find(R"("to_ugv":1)"), 10, R"("to_ugv":9)");
  const auto ugv = gs::parse_request(bad_ugv, 2);
  ASSERT_EQ(ugv.op, gs::ApiOp::Invalid);
  EXPECT_NE(ugv.error.find("to_ugv"), std::string::npos) << ugv.error;
  EXPECT_EQ(ugv.field, "to_ugv") << ugv.error;

  std::string text_speed = task_with_vmax(R"("fast")");
  const auto typed = gs::parse_request(text_speed, 2);
  ASSERT_EQ(typed.op, gs::ApiOp::Invalid);
  EXPECT_EQ(typed.field, "vmax_m_s") << typed.error;
}

TEST(GroundStationApi, MalformedAndOversizedAreRefusedWithAReason) {
  for (const char* text :
       {"", "{", "[]", "42", R"({"op":7})", R"({"op":"fly"})",
        R"({"op":"fc","uav_id":-1,"command":"arm"})", R"({"op":"fc","uav_id":0,"command":"flip"})",
        R"({"op":"abort","task_id":""})", R"({"op":"abort","task_id":"a\u0001b"})",
        R"({"op":"record","action":"pause"})", R"({"op":"submit","task":[]})"}) {
    const auto r = gs::parse_request(text, 2);
    EXPECT_EQ(r.op, gs::ApiOp::Invalid) << text;
    EXPECT_FALSE(r.error.empty()) << text;
  }
  const std::string big =
      R"({"op":"abort","task_id":")" + std::string(gs::kMaxRequestBytes, 'x') + "\"}";
  const auto r = gs::parse_request(big, 2);
  EXPECT_EQ(r.op, gs::ApiOp::Invalid);
  EXPECT_NE(r.error.find("at most"), std::string::npos);
  EXPECT_TRUE(gs::needs_token(gs::ApiOp::Fc));
  EXPECT_FALSE(gs::needs_token(gs::ApiOp::Invalid));
}

TEST(GroundStationApi, ReplyIsJsonWhateverTheBytes) {
  const std::string reply = gs::reply_json("r\xff", false, "bad \xc3(", "vmax_m_s");
  const auto j = nlohmann::json::parse(reply);
  EXPECT_EQ(j["type"], "reply");
  EXPECT_EQ(j["field"], "vmax_m_s");
}

TEST(GroundStationAccess, LoopbackReadsWithoutTokenButAWrongOneIsRefused) {
  gs::AccessPolicy loopback{"0123456789abcdef0123456789abcdef", false};
  auto d = gs::check_request(loopback, "/", "", "127.0.0.1:8080", "");
  EXPECT_EQ(d.status, 200);
  EXPECT_FALSE(d.has_token);
  d = gs::check_request(loopback, "/ws?token=0123456789abcdef0123456789abcdef", "",
                        "127.0.0.1:8080", "http://127.0.0.1:8080");
  EXPECT_EQ(d.status, 200);
  EXPECT_TRUE(d.has_token);
  d = gs::check_request(loopback, "/ws?token=0123456789abcdef0123456789abcdee", "",
                        "127.0.0.1:8080", "");
  EXPECT_EQ(d.status, 401);
}

TEST(GroundStationAccess, NetworkBindNeedsTheTokenOnEveryRequest) {
  gs::AccessPolicy network{"0123456789abcdef0123456789abcdef", true};
  EXPECT_EQ(gs::check_request(network, "/", "", "10.0.0.2:8080", "").status, 401);
  EXPECT_EQ(gs::check_request(network, "/app.js", "Bearer 0123456789abcdef0123456789abcdef",
                              "10.0.0.2:8080", "")
                .status,
            200);
  EXPECT_EQ(gs::check_request(network, "/?a=1&token=0123456789abcdef0123456789abcdef", "",
                              "10.0.0.2:8080", "")
                .status,
            200);
}

TEST(GroundStationAccess, OriginMustBeTheServedHost) {
  gs::AccessPolicy policy{"0123456789abcdef0123456789abcdef", false};
  EXPECT_EQ(gs::check_request(policy, "/ws", "", "127.0.0.1:8080", "http://evil.example").status,
            403);
  EXPECT_EQ(gs::check_request(policy, "/ws", "", "127.0.0.1:8080", "http://127.0.0.1:9999").status,
            403);
  EXPECT_EQ(gs::check_request(policy, "/ws", "", "", "").status, 400);
}

TEST(GroundStationAccess, StaticFilesArePlainNamesOnly) {
  EXPECT_EQ(gs::static_file("/"), "index.html");
  EXPECT_EQ(gs::static_file("/app.js?token=x"), "app.js");
  EXPECT_EQ(gs::static_file("/img/a.png"), "img/a.png");
  for (const char* bad :
       {"/../etc/passwd", "/a/../../b", "/.git/config", "//etc", "/a%2e%2e", "relative", "/a\\b"}) {
    EXPECT_FALSE(gs::static_file(bad).has_value()) << bad;
  }
  EXPECT_TRUE(gs::is_loopback("127.0.0.1"));
  EXPECT_TRUE(gs::is_loopback("::1"));
  EXPECT_FALSE(gs::is_loopback("0.0.0.0"));
  EXPECT_EQ(gs::make_token().size(), 32u);
  EXPECT_NE(gs::make_token(), gs::make_token());
}
