#include "cover/mavlink/message_table.hpp"

#include <array>

namespace cover::mavlink {

namespace {

// common.xml (checked against node-mavlink 2.3.0's generated definitions; EVENT and
// CURRENT_EVENT_SEQUENCE, which it lacks, against the CRC rule over common.xml's fields) and
// ardupilotmega.xml's EKF_STATUS_REPORT. ATTITUDE and SYSTEM_TIME have no struct but
// autopilots stream them on every link: knowing them lets their checksum be checked.
constexpr std::array<MessageInfo, 27> kMessages{{
    {0, 50, 9, "HEARTBEAT"},
    {1, 124, 43, "SYS_STATUS"},
    {2, 137, 12, "SYSTEM_TIME"},
    {20, 214, 20, "PARAM_REQUEST_READ"},
    {22, 220, 25, "PARAM_VALUE"},
    {23, 168, 23, "PARAM_SET"},
    {26, 170, 24, "SCALED_IMU"},
    {30, 39, 28, "ATTITUDE"},
    {31, 246, 48, "ATTITUDE_QUATERNION"},
    {32, 185, 28, "LOCAL_POSITION_NED"},
    {76, 152, 33, "COMMAND_LONG"},
    {77, 143, 10, "COMMAND_ACK"},
    {82, 49, 51, "SET_ATTITUDE_TARGET"},
    {83, 22, 37, "ATTITUDE_TARGET"},
    {93, 47, 81, "HIL_ACTUATOR_CONTROLS"},
    {105, 93, 63, "HIGHRES_IMU"},
    {107, 108, 65, "HIL_SENSOR"},
    {111, 34, 18, "TIMESYNC"},
    {113, 124, 39, "HIL_GPS"},
    {115, 4, 64, "HIL_STATE_QUATERNION"},
    {147, 154, 54, "BATTERY_STATUS"},
    {193, 71, 26, "EKF_STATUS_REPORT"},
    {230, 163, 42, "ESTIMATOR_STATUS"},
    {245, 130, 2, "EXTENDED_SYS_STATE"},
    {253, 83, 54, "STATUSTEXT"},
    {410, 160, 53, "EVENT"},
    {411, 106, 3, "CURRENT_EVENT_SEQUENCE"},
}};

}  // namespace

std::optional<MessageInfo> message_info(std::uint32_t message_id) {
  for (const MessageInfo& info : kMessages) {
    if (info.id == message_id) return info;
  }
  return std::nullopt;
}

}  // namespace cover::mavlink
