#pragma once

namespace cover::fc_bridge {

struct HoverThrustEstimatorParams {
  double initial = 0.4905;  // normalised thrust that hovers, first guess
  double min = 0.15;
  double max = 0.85;
  double initial_std = 0.1;
  double noise_per_sqrt_s = 0.0015;  // random walk of the truth (battery sag, payload)
  double accel_noise_m_s2 = 1.0;
  double gravity_m_s2 = 9.81;
  // The autopilot's vertical velocity (LOCAL_POSITION_NED): its 1-sigma noise, how far the
  // true velocity departs from the thrust model per sqrt(s) (drag, wind, the motors' lag),
  // and how old the last sample may be before the velocity is given up.
  double velocity_noise_m_s = 0.05;
  double velocity_model_noise_m_s_per_sqrt_s = 0.02;
  double velocity_timeout_s = 0.5;
  // The vertical acceleration per m/s of vertical speed that opposes it (air drag over the
  // mass, the rotors' loss of thrust in a climb), 1/s. Without it a thrust error that drag
  // balances at a steady speed looks to the velocity model like the right thrust.
  double velocity_drag_per_s = 0.0;
};

// Online estimate of the normalised thrust that hovers: a Kalman filter as PX4's
// mc_hover_thrust_estimator, fed with the commanded thrust u and the specific force the
// IMU measures along the body's up axis, f = g u / u_hover (the thrust acts along that
// axis, so the tilt does not enter; PX4 uses the world vertical because its input is the
// estimated acceleration, not the IMU's).
//
// When the autopilot gives its own vertical velocity, the filter carries it as a second
// state, v' = g u cos(tilt) / u_hover - g - d v (d: velocity_drag_per_s), and corrects both
// with each velocity sample: an error of 1 % in the hover thrust is 0.1 m/s^2 of vertical
// acceleration, which a noisy accelerometer (PX4 SIH: 1.4 m/s^2) hides for seconds but the
// velocity shows within one. Without velocity samples (none yet, or none for
// velocity_timeout_s) it is the accelerometer alone. The estimate stays within [min, max].
// The caller decides when a measurement counts: in the air, flying our thrust.
class HoverThrustEstimator {
 public:
  explicit HoverThrustEstimator(const HoverThrustEstimatorParams& params);

  // One measurement at `now_s`: commanded thrust in (0, 1], body-up specific force in
  // m/s^2 (HIGHRES_IMU's zacc negated). False when it was not usable (not finite, absurd).
  bool update(double thrust, double specific_force_up_m_s2, double now_s);
  // The autopilot's vertical velocity (up, m/s) at `now_s`, the thrust commanded since the
  // last sample. False when not usable.
  bool update_velocity(double thrust, double velocity_up_m_s, double now_s);
  // cos(tilt) of the body's up axis from the vertical, for the velocity model (1: level,
  // the assumption until an attitude is given).
  void set_tilt_cos(double tilt_cos);
  double estimate() const { return hover_; }
  // Starts again from `initial` with the initial doubt (the autopilot's own hover thrust,
  // read before the flight). False when `initial` is not a usable thrust.
  bool restart_from(double initial);
  // Whether any measurement was taken since construction or the last restart.
  bool learning() const { return last_update_s_ >= 0.0; }
  // Whether the autopilot's velocity aids the estimate now.
  bool velocity_aided() const { return velocity_known_; }
  double standard_deviation() const;

 private:
  void predict(double thrust, double now_s);
  void drop_stale_velocity(double now_s);

  HoverThrustEstimatorParams params_;
  double hover_;
  // Covariance of (hover, velocity); the velocity terms only while velocity_known_.
  double p_hh_;
  double p_hv_ = 0.0;
  double p_vv_ = 0.0;
  double velocity_ = 0.0;  // up, m/s
  bool velocity_known_ = false;
  double last_velocity_s_ = -1.0;
  double tilt_cos_ = 1.0;
  double last_update_s_ = -1.0;
};

}  // namespace cover::fc_bridge
