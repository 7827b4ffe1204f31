#include "cover/ground_station/api.hpp"

#include <yaml-cpp/yaml.h>

#include <cctype>
#include <exception>

#include "cover/config/config_error.hpp"
#include "cover/mission/task_file.hpp"

namespace cover::ground_station {
namespace {

using Json = nlohmann::json;

ApiRequest invalid(ApiRequest r, std::string error, std::string field = "") {
  r.op = ApiOp::Invalid;
  r.error = std::move(error);
  r.field = std::move(field);
  return r;
}

bool printable(const std::string& s) {
  for (const char c : s) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return false;
  }
  return true;
}

// A string field: present, a string, at most `max` printable bytes.
std::optional<std::string> text_field(const Json& j, const char* key, std::size_t max,
                                      std::string& error) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_string()) {
    error = std::string(key) + ": missing or not a string";
    return std::nullopt;
  }
  auto s = it->get<std::string>();
  if (s.size() > max || !printable(s)) {
    error = std::string(key) + ": at most " + std::to_string(max) + " printable characters";
    return std::nullopt;
  }
  return s;
}

ApiRequest parse_submit(ApiRequest r, const Json& j, int ugv_count) {
  const auto task = j.find("task");
  if (task == j.end() || !task->is_object())
    return invalid(r, "task: missing or not an object", "task");
  try {
    // JSON is YAML: the task is read and checked exactly as a task file is.
    r.task = mission::load_task(YAML::Load(task->dump()), "task", ugv_count);
  } catch (const config::ConfigError& e) {
    return invalid(r, e.what(), field_of_error(e.what()));
  } catch (const std::exception& e) {
    return invalid(r, std::string("task: ") + e.what(), "task");
  }
  r.op = ApiOp::Submit;
  return r;
}

ApiRequest parse_abort(ApiRequest r, const Json& j) {
  std::string error;
  const auto task_id = text_field(j, "task_id", 256, error);
  if (!task_id || task_id->empty())
    return invalid(r, error.empty() ? "task_id: empty" : error, "task_id");
  r.task_id = *task_id;
  r.reason = "operator (ground station)";
  if (j.contains("reason")) {
    const auto reason = text_field(j, "reason", kMaxReasonBytes, error);
    if (!reason) return invalid(r, error, "reason");
    if (!reason->empty()) r.reason = *reason;
  }
  r.op = ApiOp::Abort;
  return r;
}

ApiRequest parse_fc(ApiRequest r, const Json& j) {
  const auto uav = j.find("uav_id");
  if (uav == j.end() || !uav->is_number_unsigned() || uav->get<std::uint64_t>() > 255)
    return invalid(r, "uav_id: missing or not an integer in 0..255", "uav_id");
  r.uav_id = uav->get<std::uint32_t>();
  std::string error;
  const auto command = text_field(j, "command", 16, error);
  if (!command) return invalid(r, error, "command");
  if (*command == "arm")
    r.fc = FcCommand::Arm;
  else if (*command == "offboard")
    r.fc = FcCommand::Offboard;
  else if (*command == "land")
    r.fc = FcCommand::Land;
  else if (*command == "disarm")
    r.fc = FcCommand::Disarm;
  else
    return invalid(r, "command: not one of arm | offboard | land | disarm", "command");
  r.op = ApiOp::Fc;
  return r;
}

ApiRequest parse_record(ApiRequest r, const Json& j) {
  std::string error;
  const auto action = text_field(j, "action", 16, error);
  if (!action || (*action != "start" && *action != "stop"))
    return invalid(r, "action: not one of start | stop", "action");
  r.record_start = *action == "start";
  r.op = ApiOp::Record;
  return r;
}

}  // namespace

ApiRequest parse_request(std::string_view text, int ugv_count) {
  ApiRequest r;
  if (text.size() > kMaxRequestBytes) {
    return invalid(r, "request of " + std::to_string(text.size()) + " bytes: at most " +
                          std::to_string(kMaxRequestBytes));
  }
  Json j = Json::parse(text.begin(), text.end(), nullptr, false);
  if (j.is_discarded() || !j.is_object()) return invalid(r, "not a JSON object");
  const auto id = j.find("id");
  if (id != j.end()) {
    if (!id->is_string() || id->get<std::string>().size() > kMaxIdBytes ||
        !printable(id->get<std::string>()))
      return invalid(r, "id: a string of at most 64 printable characters", "id");
    r.id = id->get<std::string>();
  }
  const auto op = j.find("op");
  if (op == j.end() || !op->is_string()) return invalid(r, "op: missing or not a string", "op");
  const std::string name = op->get<std::string>();
  if (name == "submit") return parse_submit(std::move(r), j, ugv_count);
  if (name == "abort") return parse_abort(std::move(r), j);
  if (name == "fc") return parse_fc(std::move(r), j);
  if (name == "record") return parse_record(std::move(r), j);
  return invalid(r, "op: not one of submit | abort | fc | record", "op");
}

bool needs_token(ApiOp op) {
  return op != ApiOp::Invalid;
}

const char* fc_command_name(FcCommand command) {
  switch (command) {
    case FcCommand::Arm:
      return "arm";
    case FcCommand::Offboard:
      return "offboard";
    case FcCommand::Land:
      return "land";
    case FcCommand::Disarm:
      return "disarm";
  }
  return "?";
}

const char* op_name(ApiOp op) {
  switch (op) {
    case ApiOp::Invalid:
      return "invalid";
    case ApiOp::Submit:
      return "submit";
    case ApiOp::Abort:
      return "abort";
    case ApiOp::Fc:
      return "fc";
    case ApiOp::Record:
      return "record";
  }
  return "?";
}

std::string field_of_error(const std::string& message) {
  const auto colon = message.find(": ");
  if (colon == std::string::npos) return "";
  std::string path = message.substr(0, colon);
  const auto dot = path.rfind('.');
  if (dot == std::string::npos) return "";
  std::string key = path.substr(dot + 1);
  const auto bracket = key.find('[');
  if (bracket != std::string::npos) key = key.substr(0, bracket);
  for (const char c : key) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return "";
  }
  return key;
}

std::string reply_json(const std::string& id, bool ok, const std::string& message,
                       const std::string& field) {
  Json j{{"type", "reply"}, {"id", id}, {"ok", ok}, {"message", message}};
  if (!field.empty()) j["field"] = field;
  // Replace: a reason may quote bytes that are not UTF-8.
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

}  // namespace cover::ground_station
