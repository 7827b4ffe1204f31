#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cover/fc_bridge/autopilot_profile.hpp"
#include "cover/mavlink/parameter_messages.hpp"

namespace cover::fc_bridge {

// How much a parameter's value matters to COVER.
enum class ParameterWeight {
  Blocking,  // a wrong value makes COVER's flight wrong or unsafe: every task is held
  Advisory,  // a wrong value takes a failsafe or an arming check away from COVER's design
  Info,      // COVER reads it (a delay, the hover thrust): any value is right
};
const char* to_string(ParameterWeight weight);

// What a value may be judged against besides constants: the link as the bridge speaks on it.
struct ParameterContext {
  int bridge_system_id = 0;  // the system id of the bridge's own frames; 0: not known yet
};

// A parameter COVER depends on, what it needs and why. `names`: the parameter under each
// name it has had, newest first (ArduPilot 4.7 renamed SYSID_THISMAV to MAV_SYSID).
struct ParameterRule {
  std::vector<std::string> names;
  ParameterWeight weight = ParameterWeight::Info;
  std::string needed;  // in words: "0", "bit 3 (8) set"
  std::string why;
  bool (*acceptable)(double value) = nullptr;  // nullptr: any value
  // For a value that must agree with the link rather than a constant (ArduPilot's
  // MAV_GCS_SYSID: the bridge's own system id); nullptr: not asked.
  bool (*acceptable_on_link)(double value, const ParameterContext& context) = nullptr;
};
std::vector<ParameterRule> parameter_rules(Autopilot kind);

// A parameter as read and judged.
struct ParameterFinding {
  std::string name;  // the name the autopilot answered to (or the newest, unanswered)
  bool known = false;
  bool absent = false;  // asked under every name, never answered
  double value = 0.0;
  ParameterWeight weight = ParameterWeight::Info;
  std::string needed;
  std::string why;
  bool ok = true;  // known and acceptable (or any value will do)
};

// Reads the parameters COVER depends on (PARAM_REQUEST_READ by name, each in flight at
// once, one request per call; `timeout_s` per try, `tries` tries per name before the next name is
// tried) and judges them. Read again every `refresh_s` (an operator may change one between flights)
// and from scratch when the link is relearned (a reboot). An autopilot answers an unknown name with
// nothing at all.
class ParameterCheck {
 public:
  ParameterCheck(std::vector<ParameterRule> rules, mavlink::ParamEncoding encoding,
                 double timeout_s, int tries, double refresh_s);

  void restart(double now_s);
  // The link the values are judged against (the bridge learns its system id from the
  // autopilot's HEARTBEAT); every value already known is judged again.
  void set_context(const ParameterContext& context);
  std::optional<mavlink::ParamRequestRead> next_request(double now_s);
  // A PARAM_VALUE from the autopilot; true when it answered one of ours (news to log).
  bool on_value(const mavlink::ParamValue& value, double now_s);

  const std::vector<ParameterFinding>& findings() const { return findings_; }
  // The first wrong Blocking parameter in words, empty when none (or not read yet).
  std::string flight_blocker() const;
  // A known value by any of its names.
  std::optional<double> value(const std::string& name) const;
  bool complete() const;  // every parameter read or given up on, at least once

 private:
  struct Reading {
    std::size_t name_index = 0;
    int tries = 0;
    double deadline_s = -1.0;  // of the request in flight, < 0: none
    bool done = false;         // known or absent in this round
  };
  void judge(std::size_t index, const std::string& name, double value);

  std::vector<ParameterRule> rules_;
  ParameterContext context_;
  std::vector<ParameterFinding> findings_;
  std::vector<Reading> readings_;
  mavlink::ParamEncoding encoding_;
  double timeout_s_;
  int tries_;
  double refresh_s_;
  double round_start_s_ = 0.0;
  bool round_started_ = false;
  bool complete_once_ = false;
};

}  // namespace cover::fc_bridge
