#include "cover/sim/fc/battery_model.hpp"

#include <algorithm>
#include <cmath>

namespace cover::sim::fc {

void BatteryModel::update(double dt_s, double thrust_over_hover) {
  const double load = std::max(0.0, std::isfinite(thrust_over_hover) ? thrust_over_hover : 0.0);
  current_a_ = params_.idle_current_a + params_.hover_current_a * std::pow(load, 1.5);
  if (dt_s > 0.0) consumed_mah_ += current_a_ * dt_s * (1000.0 / 3600.0);
}

double BatteryModel::remaining() const {
  return std::clamp(1.0 - consumed_mah_ / params_.capacity_mah, 0.0, 1.0);
}

double BatteryModel::voltage_v() const {
  const double open_circuit_cell_v =
      params_.cell_empty_v + (params_.cell_full_v - params_.cell_empty_v) * remaining();
  return std::max(
      0.0, params_.cells * open_circuit_cell_v - current_a_ * params_.internal_resistance_ohm);
}

}  // namespace cover::sim::fc
