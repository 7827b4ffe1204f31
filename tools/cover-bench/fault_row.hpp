#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

// One row of the fault benchmarks (`cover-bench faults`, `cover-bench wifi`): what a fault
// did to one seeded mission, in the JSON both print under "rows".
namespace cover::bench {

enum class FaultOutcome { Completed, LandedSafely, Crashed };

inline const char* to_string(FaultOutcome outcome) {
  switch (outcome) {
    case FaultOutcome::Completed:
      return "completed";
    case FaultOutcome::LandedSafely:
      return "landed_safely";
    case FaultOutcome::Crashed:
      return "crashed";
  }
  return "crashed";
}

struct FaultRow {
  std::string fault;  // uav_agent_kill, ugv_agent_kill, ..., wifi_loss
  std::string mix;    // the DDS vendors: fastdds, cyclone, mixed
  int seed = 0;
  std::optional<double> time_to_failsafe_ms;  // none: no failsafe was entered
  FaultOutcome outcome = FaultOutcome::Crashed;
  std::optional<double> touchdown_speed_m_s;  // none: not measured / no touchdown
  std::optional<double> landing_error_m;      // on the target deck; none: not landed there
};

// A finite number, or null: NaN would not be valid JSON.
inline nlohmann::json number_or_null(const std::optional<double>& value) {
  return value && std::isfinite(*value) ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

inline nlohmann::json to_json(const FaultRow& row) {
  return {{"fault", row.fault},
          {"mix", row.mix},
          {"seed", row.seed},
          {"time_to_failsafe_ms", number_or_null(row.time_to_failsafe_ms)},
          {"outcome", to_string(row.outcome)},
          {"touchdown_speed_m_s", number_or_null(row.touchdown_speed_m_s)},
          {"landing_error_m", number_or_null(row.landing_error_m)}};
}

// {"rows": [...]}: the document `--json` prints.
inline nlohmann::json rows_json(const std::vector<FaultRow>& rows) {
  nlohmann::json out{{"rows", nlohmann::json::array()}};
  for (const FaultRow& row : rows) out["rows"].push_back(to_json(row));
  return out;
}

}  // namespace cover::bench
