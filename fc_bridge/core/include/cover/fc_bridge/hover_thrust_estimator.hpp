#pragma once

namespace cover::fc_bridge {

struct HoverThrustEstimatorParams {
  double initial = 0.4905;  // normalised thrust that hovers, first guess
  double min = 0.15;
  double max = 0.85;
  double initial_std = 0.1;
  double noise_per_sqrt_s = 0.0036;  // random walk of the truth (battery sag, payload)
  double accel_noise_m_s2 = 1.0;
  double gravity_m_s2 = 9.81;
};

// Online estimate of the normalised thrust that hovers: a 1-state Kalman filter as PX4's
// mc_hover_thrust_estimator, fed with the commanded thrust u and the specific force the
// IMU measures along the body's up axis, f = g u / u_hover (the thrust acts along that
// axis, so the tilt does not enter; PX4 uses the world vertical because its input is the
// estimated acceleration, not the IMU's). The estimate stays within [min, max]. The caller
// decides when a measurement counts: in the air, flying our thrust.
class HoverThrustEstimator {
 public:
  explicit HoverThrustEstimator(const HoverThrustEstimatorParams& params);

  // One measurement at `now_s`: commanded thrust in (0, 1], body-up specific force in
  // m/s^2 (HIGHRES_IMU's zacc negated). False when it was not usable (not finite, absurd).
  bool update(double thrust, double specific_force_up_m_s2, double now_s);
  double estimate() const { return hover_; }
  // Starts again from `initial` with the initial doubt (the autopilot's own hover thrust,
  // read before the flight). False when `initial` is not a usable thrust.
  bool restart_from(double initial);
  // Whether any measurement was taken since construction or the last restart.
  bool learning() const { return last_update_s_ >= 0.0; }
  double standard_deviation() const;

 private:
  HoverThrustEstimatorParams params_;
  double hover_;
  double variance_;
  double last_update_s_ = -1.0;
};

}  // namespace cover::fc_bridge
