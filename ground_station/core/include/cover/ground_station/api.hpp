#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "cover/vocabulary/task.hpp"

namespace cover::ground_station {

// The page's requests over the WebSocket, one JSON object per text message:
//   {"op": "submit", "id": "r1", "task": {task_id, uav_id, processes: [...]}}  keys as a task file
//   {"op": "abort",  "id": "r2", "task_id": "t", "reason": "operator"}
//   {"op": "fc",     "id": "r3", "uav_id": 0, "command": "arm|offboard|land|disarm"}
//   {"op": "record", "id": "r4", "action": "start|stop"}
// Each is answered by one {"type": "reply", "id", "ok", "message", "field"?}.
inline constexpr std::size_t kMaxRequestBytes = 64 * 1024;
inline constexpr std::size_t kMaxIdBytes = 64;
inline constexpr std::size_t kMaxReasonBytes = 200;

enum class ApiOp { Invalid, Submit, Abort, Fc, Record };
enum class FcCommand { Arm, Offboard, Land, Disarm };

struct ApiRequest {
  ApiOp op = ApiOp::Invalid;
  std::string id;  // the page's, echoed in the reply ("" when it sent none or a bad one)
  // Invalid: why, and the field it is about ("" for the message as a whole).
  std::string error;
  std::string field;
  mission::Task task;        // Submit: checked as a task file's (mission::load_task)
  std::string task_id;       // Abort
  std::string reason;        // Abort
  std::uint32_t uav_id = 0;  // Fc
  FcCommand fc = FcCommand::Arm;
  bool record_start = false;  // Record
};

// Never throws; anything not a well-formed request is Invalid with a reason a person reads.
// `ugv_count`: the UGV ids a task may name, [0, ugv_count).
ApiRequest parse_request(std::string_view text, int ugv_count);

// Every op but Invalid moves a vehicle or changes the fleet: the connection must hold the token.
bool needs_token(ApiOp op);

const char* fc_command_name(FcCommand command);
const char* op_name(ApiOp op);

// The key a task-file error names ("page.processes[1].vmax_m_s: ..." -> "vmax_m_s"), "" when none.
std::string field_of_error(const std::string& message);

// {"type": "reply", ...}; `field` left out when empty.
std::string reply_json(const std::string& id, bool ok, const std::string& message,
                       const std::string& field = "");

}  // namespace cover::ground_station
