#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "cover/config/param_fields.hpp"
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
inline constexpr MotionPatternKind kMotionPatternKinds[] = {
    MotionPatternKind::Stationary, MotionPatternKind::Circle, MotionPatternKind::FigureEight,
    MotionPatternKind::Star,       MotionPatternKind::SCurve, MotionPatternKind::BackAndForth};

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

  // Each field once (config/param_fields.hpp). A pattern ignores the keys it does not use,
  // but their bounds hold whatever the kind: a stray value is a mistake all the same.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("kind", self.kind, Field("", "the motion").one_of(kMotionPatternKinds).required());
    visit("origin_m", self.origin_m,
          Field("m", "world x, y of the pattern's centre (s_curve: its start)"));
    visit("orientation_rad", self.orientation_rad,
          Field("rad", "rotation of the pattern's local x axis from world x"));
    // 5 m/s is far beyond the paper's UGVs (<= 1 m/s): anything above is a unit error.
    visit("speed_m_s", self.speed_m_s,
          Field("m/s", "circle: constant speed; other moving patterns: peak speed")
              .above(0.0)
              .at_most(5.0));
    visit("yaw_rate_rad_s", self.yaw_rate_rad_s,
          Field("rad/s",
                "circle: turn rate, left positive (radius = speed / yaw rate); "
                "|w| >= 0.001 on a circle")
              .at_least(-5.0)
              .at_most(5.0));
    visit("half_length_m", self.half_length_m,
          Field("m", "figure_eight: half extent along local x; back_and_forth: half stroke")
              .above(0.0)
              .below(1e3));
    visit("half_width_m", self.half_width_m,
          Field("m", "figure_eight: half extent along local y (> 0); s_curve: lateral amplitude")
              .at_least(0.0)
              .below(1e3));
    visit("wavelength_m", self.wavelength_m,
          Field("m", "s_curve: distance along local x of one full period (two bends)")
              .above(0.0)
              .below(1e4));
    visit("radius_m", self.radius_m, Field("m", "star: mean radius").above(0.0).below(1e3));
    visit("star_points", self.star_points,
          Field("", "star: number of tips").at_least(2.0).at_most(20.0));
    visit("star_depth", self.star_depth,
          Field("", "star: relative radius modulation (< 1 keeps the speed above 0)")
              .above(0.0)
              .at_most(0.9));
    visit("phase_rad", self.phase_rad,
          Field("rad", "start value of the curve parameter (angle on the circle, etc.)"));
  }

  static UgvMotionPatternParams load(cover::config::YamlReader& reader);
  // Throws config::ConfigError naming "<context>.<key>".
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
