#include "fc_commands.hpp"

#include <CLI/CLI.hpp>

#include <array>
#include <iostream>
#include <nlohmann/json.hpp>
#include <utility>

#include "cover/clock/clock.hpp"
#include "cover/dds/json_codec.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/wire/fc_state.hpp"
#include "fc_client.hpp"

namespace cover::cli {
namespace {

constexpr std::array<std::pair<const char*, msg::FcCommandKind>, 4> kActions{{
    {"arm", msg::FcCommandKind::FC_COMMAND_ARM},
    {"disarm", msg::FcCommandKind::FC_COMMAND_DISARM},
    {"offboard", msg::FcCommandKind::FC_COMMAND_OFFBOARD},
    {"land", msg::FcCommandKind::FC_COMMAND_LAND},
}};

std::string readable(const msg::FcState& s) {
  const auto reason = wire::fc_not_ready_reason(s);
  std::string text = "UAV " + std::to_string(s.uav_id) + ": " + msg::to_string(s.autopilot) +
                     " (system " + std::to_string(s.system_id) + "), link " +
                     (s.link_ok ? "up" : "LOST") + ", " + (s.armed ? "ARMED" : "disarmed") +
                     ", mode " + (s.mode_name.empty() ? msg::to_string(s.mode) : s.mode_name) +
                     ", " + msg::to_string(s.landed_state) + "\n";
  char line[160];
  std::snprintf(line, sizeof line,
                "  hover thrust %.3f, setpoints %.0f Hz, battery %.2f V, rx errors %u, lost %u\n",
                s.hover_thrust, s.setpoint_rate_hz, s.battery_voltage_v, s.rx_errors, s.rx_dropped);
  text += line;
  text += "  COVER flies it: " + (reason ? "no (" + *reason + ")" : std::string("yes")) + "\n";
  if (!s.failsafe.empty()) text += "  last bridge failsafe: " + s.failsafe + "\n";
  if (!s.status_text.empty()) text += "  autopilot says: " + s.status_text + "\n";
  return text;
}

}  // namespace

FcCommands::FcCommands(CLI::App& app) {
  fc_ = app.add_subcommand("fc", "A UAV's flight controller through its cover-fc-bridge");
  std::string actions = "status";
  for (const auto& [name, kind] : kActions) actions += std::string("|") + name;
  fc_->add_option("action", action_,
                  "status: the autopilot's state; arm, disarm, offboard (PX4 OFFBOARD / ArduPilot "
                  "GUIDED_NOGPS), land: a command, answered by the autopilot")
      ->required()
      ->check(CLI::IsMember({"status", "arm", "disarm", "offboard", "land"}));
  fc_->add_option("uav", uav_id_, "UAV id U")->required();
  fc_->add_option("--timeout", timeout_s_, "seconds to wait for the bridge and the autopilot")
      ->capture_default_str();
  fc_->add_flag("--json", json_, "one JSON object instead of text");
  dds_.add_to(*fc_);
  fc_->footer(
      "Exit: 0 status heard / command accepted, 1 refused by the autopilot (its reason printed),\n"
      "2 usage, 3 no bridge or no answer within --timeout. Arming is the operator's decision:\n"
      "the bridge never arms on its own (auto_arm is for simulation only).");
}

bool FcCommands::chosen() const {
  return fc_->parsed();
}

int FcCommands::run() {
  return action_ == "status" ? status() : command();
}

int FcCommands::status() {
  dds::Participant participant(dds_.resolve("cover-fc"));
  dds::Reader<msg::FcState> reader = participant.make_reader(dds::topics::fc_state(uav_id_));
  if (!reader.wait_for_sample(clock::to_milliseconds(timeout_s_))) {
    std::cerr << "no cover-fc-bridge reported for UAV " << uav_id_ << " within " << timeout_s_
              << " s (is one running on this DDS domain?)\n";
    return kFcNoAnswer;
  }
  const msg::FcState state = reader.latest()->sample;
  if (json_) {
    std::cout << dds::to_json(state).dump() << std::endl;
  } else {
    std::cout << readable(state);
  }
  return kFcAccepted;
}

int FcCommands::command() {
  msg::FcCommandKind kind = msg::FcCommandKind::FC_COMMAND_LAND;
  for (const auto& [name, value] : kActions) {
    if (action_ == name) kind = value;
  }
  dds::Participant participant(dds_.resolve("cover-fc"));
  FcClient client(participant, clock::to_milliseconds(timeout_s_));
  const std::optional<msg::FcReply> reply = client.call(uav_id_, kind);
  if (!reply) {
    std::cerr << "no answer from UAV " << uav_id_ << "'s cover-fc-bridge within " << timeout_s_
              << " s\n";
    return kFcNoAnswer;
  }
  if (json_) {
    std::cout << dds::to_json(*reply).dump() << std::endl;
  } else {
    const char* result = reply->result == msg::FcCommandResult::FC_RESULT_ACCEPTED  ? "accepted"
                         : reply->result == msg::FcCommandResult::FC_RESULT_REFUSED ? "REFUSED"
                                                                                    : "no answer";
    std::cout << action_ << " UAV " << uav_id_ << ": " << result
              << (reply->message.empty() ? "" : " (" + reply->message + ")") << "\n";
  }
  switch (reply->result) {
    case msg::FcCommandResult::FC_RESULT_ACCEPTED:
      return kFcAccepted;
    case msg::FcCommandResult::FC_RESULT_REFUSED:
      return kFcRefused;
    default:
      return kFcNoAnswer;
  }
}

}  // namespace cover::cli
