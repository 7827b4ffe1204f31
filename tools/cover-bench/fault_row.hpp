#pragma once

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace cover::bench {

// One row of `cover-bench faults` (and `wifi`): one run with one injected fault.
struct FaultRow {
  std::string fault;  // uav_agent_kill | ugv_agent_kill | relative_state_gap | mocap_dropout |
                      // imu_fault | sim_kill | wifi_loss | bridge_kill | fc_heartbeat_loss |
                      // agent_kill_with_bridge
  std::string mix;    // the DDS vendors: fastdds | cyclone | mixed
  std::uint64_t seed = 0;
  double fault_time_s = NAN;         // simulated time the fault was injected at
  double time_to_failsafe_ms = NAN;  // input lost -> failsafe entered; NaN: none entered
  std::string outcome = "crashed";   // completed | landed_safely | crashed
  double touchdown_speed_m_s = NAN;  // vertical, just before contact
  double landing_error_m = NAN;      // from the target deck's centre; NaN: not on it
  std::string detail;                // what decided the outcome, for a reader
};

inline nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

inline nlohmann::json to_json(const FaultRow& r) {
  return {{"fault", r.fault},
          {"mix", r.mix},
          {"seed", r.seed},
          {"fault_time_s", number_or_null(r.fault_time_s)},
          {"time_to_failsafe_ms", number_or_null(r.time_to_failsafe_ms)},
          {"outcome", r.outcome},
          {"touchdown_speed_m_s", number_or_null(r.touchdown_speed_m_s)},
          {"landing_error_m", number_or_null(r.landing_error_m)},
          {"detail", r.detail}};
}

// {"rows": [...]}: the document `--json` prints.
inline nlohmann::json rows_json(const std::vector<FaultRow>& rows) {
  nlohmann::json out{{"rows", nlohmann::json::array()}};
  for (const FaultRow& row : rows) out["rows"].push_back(to_json(row));
  return out;
}

}  // namespace cover::bench
