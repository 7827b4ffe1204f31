#include "cover/mavlink/message_table.hpp"

#include <array>

namespace cover::mavlink {

namespace {

// common.xml (checked against node-mavlink 2.3.0's generated definitions). ATTITUDE and
// SYSTEM_TIME have no struct in messages.hpp but autopilots stream them on every link:
// knowing them lets their checksum be checked instead of counting them as unknown.
constexpr std::array<MessageInfo, 15> kMessages{{
    {0, 50, 9, "HEARTBEAT"},
    {1, 124, 43, "SYS_STATUS"},
    {2, 137, 12, "SYSTEM_TIME"},
    {26, 170, 24, "SCALED_IMU"},
    {30, 39, 28, "ATTITUDE"},
    {31, 246, 48, "ATTITUDE_QUATERNION"},
    {76, 152, 33, "COMMAND_LONG"},
    {77, 143, 10, "COMMAND_ACK"},
    {82, 49, 51, "SET_ATTITUDE_TARGET"},
    {83, 22, 37, "ATTITUDE_TARGET"},
    {105, 93, 63, "HIGHRES_IMU"},
    {111, 34, 18, "TIMESYNC"},
    {147, 154, 54, "BATTERY_STATUS"},
    {245, 130, 2, "EXTENDED_SYS_STATE"},
    {253, 83, 54, "STATUSTEXT"},
}};

}  // namespace

std::optional<MessageInfo> message_info(std::uint32_t message_id) {
  for (const MessageInfo& info : kMessages) {
    if (info.id == message_id) return info;
  }
  return std::nullopt;
}

}  // namespace cover::mavlink
