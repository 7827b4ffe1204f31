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
  if (s.estimator_reported) {
    text +=
        std::string("  estimator: ") + (s.estimator_ok ? "" : "NOT READY: ") + s.estimator + "\n";
  }
  if (!s.streams_missing.empty()) text += "  streams missing: " + s.streams_missing + "\n";
  std::snprintf(line, sizeof line, "  frames of message types the bridge does not read: %u\n",
                s.rx_unknown);
  text += line;
  return text;
}

// Every parameter read (or given up on): what `check` waits for.
bool parameters_read(const msg::FcState& s) {
  if (s.parameters.empty()) return false;
  for (const msg::FcParameter& p : s.parameters) {
    if (!p.known && !p.absent) return false;
  }
  return true;
}

const char* weight_word(msg::FcParameterWeight weight) {
  switch (weight) {
    case msg::FcParameterWeight::FC_PARAMETER_BLOCKING:
      return "blocking";
    case msg::FcParameterWeight::FC_PARAMETER_ADVISORY:
      return "advisory";
    default:
      return "info";
  }
}

std::string parameter_table(const msg::FcState& s) {
  std::string text = "UAV " + std::to_string(s.uav_id) + ": " + msg::to_string(s.autopilot) +
                     " parameters COVER depends on\n";
  for (const msg::FcParameter& p : s.parameters) {
    char value[32];
    if (p.known) {
      std::snprintf(value, sizeof value, "%g", p.value);
    } else {
      std::snprintf(value, sizeof value, "%s", p.absent ? "absent" : "not read");
    }
    char line[160];
    std::snprintf(line, sizeof line, "  %-4s %-17s %-10s needs %s [%s]\n", p.ok ? "ok" : "BAD",
                  p.name.c_str(), value, p.needed.c_str(), weight_word(p.weight));
    text += line;
    if (!p.ok) text += "       why: " + p.why + "\n";
  }
  text += s.flight_blocker.empty() ? "  no parameter holds COVER's tasks\n"
                                   : "  TASKS ARE HELD: " + s.flight_blocker + "\n";
  return text;
}

}  // namespace

FcCommands::FcCommands(CLI::App& app) {
  fc_ = app.add_subcommand("fc", "A UAV's flight controller through its cover-fc-bridge");
  std::string actions = "status";
  for (const auto& [name, kind] : kActions) actions += std::string("|") + name;
  fc_->add_option("action", action_,
                  "status: the autopilot's state; check: the autopilot parameters COVER depends "
                  "on, each with the value it needs and why; arm, disarm, offboard (PX4 OFFBOARD "
                  "/ ArduPilot GUIDED_NOGPS), land: a command, answered by the autopilot")
      ->required()
      ->check(CLI::IsMember({"status", "check", "arm", "disarm", "offboard", "land"}));
  fc_->add_option("uav", uav_id_, "UAV id U")->required();
  fc_->add_option("--timeout", timeout_s_, "seconds to wait for the bridge and the autopilot")
      ->capture_default_str();
  fc_->add_flag("--json", json_, "one JSON object instead of text");
  dds_.add_to(*fc_);
  fc_->footer(
      "Exit: 0 status heard / command accepted / every parameter right, 1 refused by the\n"
      "autopilot (its reason printed) / a parameter wrong (named), 2 usage, 3 no bridge, no\n"
      "answer or parameters not read within --timeout. Arming is the operator's decision:\n"
      "the bridge never arms on its own (auto_arm is for simulation only).");
}

bool FcCommands::chosen() const {
  return fc_->parsed();
}

int FcCommands::run() {
  if (action_ == "status") return status();
  if (action_ == "check") return check();
  return command();
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

int FcCommands::check() {
  dds::Participant participant(dds_.resolve("cover-fc"));
  dds::Reader<msg::FcState> reader = participant.make_reader(dds::topics::fc_state(uav_id_));
  const auto deadline = clock::monotonic_ns() + clock::s_to_ns(timeout_s_);
  std::optional<msg::FcState> state;
  // The bridge reads the parameters after it finds the autopilot: each new state is looked
  // at until one has them all, or the deadline.
  for (std::uint64_t seen = 0; clock::monotonic_ns() < deadline; seen = reader.received_count()) {
    const double remaining_s = clock::ns_to_s(deadline - clock::monotonic_ns());
    if (!reader.wait_for_sample(clock::to_milliseconds(remaining_s), seen)) break;
    state = reader.latest()->sample;
    if (parameters_read(*state)) break;
  }
  if (!state || !parameters_read(*state)) {
    std::cerr << (state ? "UAV " + std::to_string(uav_id_) +
                              "'s bridge has not read the autopilot's parameters within "
                        : "no cover-fc-bridge reported for UAV " + std::to_string(uav_id_) +
                              " within ")
              << timeout_s_ << " s\n";
    return kFcNoAnswer;
  }
  bool all_ok = true;
  for (const msg::FcParameter& p : state->parameters) all_ok = all_ok && p.ok;
  if (json_) {
    nlohmann::ordered_json out;
    out["uav_id"] = state->uav_id;
    out["autopilot"] = msg::to_string(state->autopilot);
    out["ok"] = all_ok;
    out["flight_blocker"] = state->flight_blocker;
    out["auto_disarm_s"] = state->auto_disarm_s;
    out["parameters"] = nlohmann::ordered_json::array();
    for (const msg::FcParameter& p : state->parameters) {
      nlohmann::ordered_json row;
      row["name"] = p.name;
      row["known"] = p.known;
      row["absent"] = p.absent;
      if (p.known) row["value"] = p.value;
      row["weight"] = weight_word(p.weight);
      row["needed"] = p.needed;
      row["why"] = p.why;
      row["ok"] = p.ok;
      out["parameters"].push_back(row);
    }
    std::cout << out.dump() << std::endl;
  } else {
    std::cout << parameter_table(*state);
  }
  return all_ok ? kFcAccepted : kFcRefused;
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
