#include <gtest/gtest.h>

#include "cover/dds/json_codec.hpp"

using cover::dds::from_json;
using cover::dds::JsonError;
using cover::dds::to_json;
using nlohmann::json;

TEST(JsonCodec, RoundTripsNestedSequencesEnumsAndStrings) {
  cover::msg::TransitionTask task;
  task.task_id = "deliver-1";
  task.uav_id = 2;
  task.processes.resize(2);
  task.processes[1].to_ugv = 1;
  task.processes[1].final_point_m = {0.1, 0.0, 0.25};
  task.processes[1].final_action = cover::msg::FinalAction::FINAL_ACTION_DELIVER;
  const json encoded = to_json(task);
  EXPECT_EQ(encoded["processes"][1]["final_action"], "FINAL_ACTION_DELIVER");
  EXPECT_EQ(from_json<cover::msg::TransitionTask>(encoded), task);
}

TEST(JsonCodec, MissingFieldsTakeTheirZeroValue) {
  const auto imu = from_json<cover::msg::UgvImu>(json::parse(R"({"ugv_id": 3})"));
  EXPECT_EQ(imu.ugv_id, 3u);
  EXPECT_EQ(imu.stamp_ns, 0);
  EXPECT_EQ(imu.specific_force_m_s2.z, 0.0);
}

TEST(JsonCodec, UnknownFieldIsAnErrorNamingIt) {
  try {
    from_json<cover::msg::UgvImu>(json::parse(R"({"specific_force_m_s2": {"x": 1, "w": 2}})"));
    FAIL() << "expected JsonError";
  } catch (const JsonError& e) {
    EXPECT_NE(std::string(e.what()).find("'w'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("specific_force_m_s2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(from_json<cover::msg::UgvImu>(json::parse(R"({"gyro": 1})")), JsonError);
}

TEST(JsonCodec, WrongTypesAreErrors) {
  EXPECT_THROW(from_json<cover::msg::UgvImu>(json::parse(R"({"ugv_id": "one"})")), JsonError);
  EXPECT_THROW(from_json<cover::msg::UgvImu>(json::parse(R"({"ugv_id": -1})")), JsonError);
  EXPECT_THROW(from_json<cover::msg::UgvImu>(json::parse(R"({"ugv_id": 1.5})")), JsonError);
  EXPECT_THROW(from_json<cover::msg::UavStatus>(json::parse(R"({"stage": "STAGE_LANDED"})")),
               JsonError);
  EXPECT_THROW(from_json<cover::msg::UavCommand>(json::parse(R"({"armed": 1})")), JsonError);
  EXPECT_THROW(from_json<cover::msg::UgvImu>(json::parse("[1, 2]")), JsonError);
}
