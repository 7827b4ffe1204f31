#pragma once

#include "cover/sim/fc/sim_fc_params.hpp"

namespace cover::sim::fc {

// The flight battery as the autopilot's power module measures it: charge drawn by the
// motors (current rising with thrust^1.5 from the hover current) and the electronics, an
// open-circuit voltage falling linearly with the charge used, and the sag of the pack's
// internal resistance under load.
class BatteryModel {
 public:
  explicit BatteryModel(const BatteryParams& params) : params_(params) {}

  // Draws for `dt_s` at `thrust_over_hover` (plant thrust / hover thrust; 0 with the
  // motors off).
  void update(double dt_s, double thrust_over_hover);

  double voltage_v() const;
  double current_a() const { return current_a_; }
  double consumed_mah() const { return consumed_mah_; }
  double remaining() const;  // 0..1
  double cell_voltage_v() const { return voltage_v() / params_.cells; }
  int cells() const { return params_.cells; }

 private:
  BatteryParams params_;
  double current_a_ = 0.0;
  double consumed_mah_ = 0.0;
};

}  // namespace cover::sim::fc
