#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "cover/config/yaml_reader.hpp"

namespace cover::sim {

// The paper's UGV motions (docs/model.md, scenarios). Every pattern is a C-infinity
// parametric planar curve, so velocity, acceleration, yaw rate and yaw acceleration are
// analytic and the simulated IMU is meaningful. Each curve is defined in a local frame
// L (origin `origin_m`, x axis rotated by `orientation_rad` from world x):
//
//   stationary     p = 0; yaw = orientation.
//   circle         p = R [cos th, sin th], th = phase + w t, R = v / w (signed).
//                  Speed |v|, yaw rate w, centripetal acceleration v w toward the centre.
//   figure_eight   p = [A sin ph, W sin 2ph], ph = phase + Om t (a Lissajous 1:2 eight);
//                  A = half_length_m, W = half_width_m; the speed peaks at the crossing
//                  (ph = 0, pi) where it equals speed_m_s: Om = v / sqrt(A^2 + 4 W^2).
//                  The speed never vanishes (cos ph and cos 2ph never vanish together).
//   star           p = r(ph) [cos ph, sin ph], r = R (1 + e cos(n ph)), ph = phase + Om t;
//                  R = radius_m, n = star_points, e = star_depth (< 1 keeps r > 0, so the
//                  speed never vanishes); Om scales the peak speed to speed_m_s.
//   s_curve        p = [u t, W sin(k u t + phase)], k = 2 pi / wavelength_m, W = half_width_m;
//                  drives along local +x forever (give two UGVs opposite orientations);
//                  peak speed at the inflections: u = v / sqrt(1 + (W k)^2).
//   back_and_forth p = [L sin(phase + Om t), 0], L = half_length_m, Om = v / L: a smooth
//                  reciprocating line, peak speed v mid-stroke. The vehicle reverses, so its
//                  heading stays along local x (it drives backwards on the return stroke).
//
// Heading is along the velocity for every pattern except stationary and back_and_forth.
enum class MotionPatternKind { Stationary, Circle, FigureEight, Star, SCurve, BackAndForth };

const char* to_string(MotionPatternKind kind);
std::optional<MotionPatternKind> parse_motion_pattern_kind(const std::string& name);

struct UgvMotionPatternParams {
  MotionPatternKind kind = MotionPatternKind::Stationary;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  // centre (start point for s_curve)
  double orientation_rad = 0.0;                        // rotation of the local frame from world x
  double speed_m_s = 0.5;                              // circle: constant speed; others: peak speed
  double yaw_rate_rad_s = 0.35;  // circle only: turn rate, sign = direction (left > 0)
  double half_length_m = 2.0;    // figure_eight: half extent along x; back_and_forth: half stroke
  double half_width_m = 1.0;     // figure_eight: half extent along y; s_curve: amplitude
  double wavelength_m = 8.0;     // s_curve: length along x of one full period (two S bends)
  double radius_m = 2.0;         // star: mean radius
  int star_points = 5;           // star: number of tips
  double star_depth = 0.2;       // star: relative radius modulation, in (0, 0.9]
  double phase_rad = 0.0;        // start value of the curve parameter (th / ph)

  static UgvMotionPatternParams load(cover::config::YamlReader& reader);
  void validate(const std::string& context = "pattern") const;
};

// Planar kinematics of a UGV at one instant, in the world frame.
struct UgvKinematics {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity_m_s = Eigen::Vector2d::Zero();
  Eigen::Vector2d acceleration_m_s2 = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;
  double yaw_rate_rad_s = 0.0;
  double yaw_acceleration_rad_s2 = 0.0;
};

class UgvMotionPattern {
 public:
  // `params` must have passed validate().
  explicit UgvMotionPattern(const UgvMotionPatternParams& params);

  UgvKinematics at(double t_s) const;
  const UgvMotionPatternParams& params() const { return params_; }

 private:
  // Position and its first three time derivatives, in the local frame.
  struct LocalCurve {
    Eigen::Vector2d p, dp, ddp, dddp;
  };
  LocalCurve local_curve(double t_s) const;
  bool heading_follows_velocity() const;

  UgvMotionPatternParams params_;
  double parameter_rate_ = 0.0;  // d(curve parameter)/dt, 1/s (m/s for s_curve's u)
};

}  // namespace cover::sim
