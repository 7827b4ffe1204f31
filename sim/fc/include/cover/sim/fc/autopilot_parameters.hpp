#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cover/mavlink/parameter_messages.hpp"
#include "cover/sim/fc/autopilot_mode.hpp"
#include "cover/sim/fc/sim_fc_params.hpp"

namespace cover::sim::fc {

// One parameter as the firmware declares it: its name, MAV_PARAM_TYPE and value.
struct AutopilotParameter {
  std::string name;
  std::uint8_t type = 9;  // MAV_PARAM_TYPE
  double value = 0.0;
};

// The parameters a simulated autopilot answers PARAM_REQUEST_READ for: those COVER's bridge
// reads (docs/flight-controller.md), with the types the real firmware gives them (read from
// PX4 SITL and ArduCopter SITL, docs/autopilots.md), their values from config/sim/sim_fc.yaml.
class AutopilotParameters {
 public:
  AutopilotParameters(Autopilot profile, const SimFcParams& params, std::uint8_t system_id);

  std::optional<std::size_t> index_of(const std::string& name) const;
  std::size_t size() const { return table_.size(); }
  const AutopilotParameter& at(std::size_t index) const { return table_[index]; }
  // The PARAM_VALUE of parameter `index` in the autopilot's encoding (PX4 copies an
  // integer's bytes into the float, ArduPilot converts it); `by_name`: ArduPilot then
  // answers param_index 65535, PX4 the parameter's index (both measured).
  mavlink::ParamValue value_message(std::size_t index, bool by_name) const;

 private:
  Autopilot profile_;
  mavlink::ParamEncoding encoding_;
  std::vector<AutopilotParameter> table_;
};

}  // namespace cover::sim::fc
