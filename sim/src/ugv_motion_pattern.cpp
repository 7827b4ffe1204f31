#include "cover/sim/ugv_motion_pattern.hpp"

#include <algorithm>
#include <cmath>

#include "cover/vocabulary/angles.hpp"

namespace cover::sim {

namespace {

struct KindName {
  MotionPatternKind kind;
  const char* name;
};
constexpr KindName kKindNames[] = {
    {MotionPatternKind::Stationary, "stationary"},
    {MotionPatternKind::Circle, "circle"},
    {MotionPatternKind::FigureEight, "figure_eight"},
    {MotionPatternKind::Star, "star"},
    {MotionPatternKind::SCurve, "s_curve"},
    {MotionPatternKind::BackAndForth, "back_and_forth"},
};

// Peak of |dp/dph| for the star curve. With c = cos(n ph):
// |dp/dph|^2 = R^2 [(1 + e c)^2 + e^2 n^2 (1 - c^2)], a concave quadratic in c (n >= 2);
// its maximum over c in [-1, 1] is at c* = 1 / (e (n^2 - 1)), clipped.
double star_peak_speed_per_rate(double radius, double depth, int points) {
  const double n2 = static_cast<double>(points) * points;
  const double c = std::clamp(1.0 / (depth * (n2 - 1.0)), -1.0, 1.0);
  const double r = 1.0 + depth * c;
  return radius * std::sqrt(r * r + depth * depth * n2 * (1.0 - c * c));
}

Eigen::Vector2d rotate(const Eigen::Vector2d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

const char* to_string(MotionPatternKind kind) {
  for (const auto& entry : kKindNames) {
    if (entry.kind == kind) return entry.name;
  }
  return "unknown";
}

std::optional<MotionPatternKind> parse_motion_pattern_kind(const std::string& name) {
  for (const auto& entry : kKindNames) {
    if (name == entry.name) return entry.kind;
  }
  return std::nullopt;
}

UgvMotionPatternParams UgvMotionPatternParams::load(cover::config::YamlReader& reader) {
  UgvMotionPatternParams p;
  cover::config::load_fields(p, reader);
  p.validate(reader.context());
  return p;
}

void UgvMotionPatternParams::validate(const std::string& context) const {
  cover::config::check_fields(*this, context);
  // What a kind needs beyond the bounds every kind keeps.
  if (kind == MotionPatternKind::Circle) {
    cover::config::check(std::abs(yaw_rate_rad_s) >= 1e-3, context + ".yaw_rate_rad_s",
                         "must be non-zero on a circle, |w| >= 0.001");
  }
  if (kind == MotionPatternKind::FigureEight) {
    cover::config::check(half_width_m > 0.0, context + ".half_width_m",
                         "must be > 0 on a figure_eight");
  }
}

UgvMotionPattern::UgvMotionPattern(const UgvMotionPatternParams& params) : params_(params) {
  const double v = params_.speed_m_s;
  switch (params_.kind) {
    case MotionPatternKind::Stationary:
      parameter_rate_ = 0.0;
      break;
    case MotionPatternKind::Circle:
      parameter_rate_ = params_.yaw_rate_rad_s;
      break;
    case MotionPatternKind::FigureEight:
      parameter_rate_ = v / std::hypot(params_.half_length_m, 2.0 * params_.half_width_m);
      break;
    case MotionPatternKind::Star:
      parameter_rate_ =
          v / star_peak_speed_per_rate(params_.radius_m, params_.star_depth, params_.star_points);
      break;
    case MotionPatternKind::SCurve: {
      const double wave_number = model::kTwoPi / params_.wavelength_m;
      parameter_rate_ = v / std::hypot(1.0, params_.half_width_m * wave_number);
      break;
    }
    case MotionPatternKind::BackAndForth:
      parameter_rate_ = v / params_.half_length_m;
      break;
  }
}

bool UgvMotionPattern::heading_follows_velocity() const {
  return params_.kind != MotionPatternKind::Stationary &&
         params_.kind != MotionPatternKind::BackAndForth;
}

UgvMotionPattern::LocalCurve UgvMotionPattern::local_curve(double t_s) const {
  LocalCurve c{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(),
               Eigen::Vector2d::Zero()};
  const double rate = parameter_rate_;
  const double ph = params_.phase_rad + rate * t_s;
  switch (params_.kind) {
    case MotionPatternKind::Stationary:
      break;
    case MotionPatternKind::Circle: {
      const double radius = params_.speed_m_s / params_.yaw_rate_rad_s;  // signed
      const Eigen::Vector2d e(std::cos(ph), std::sin(ph));
      const Eigen::Vector2d e_perp(-e.y(), e.x());
      c.p = radius * e;
      c.dp = radius * rate * e_perp;
      c.ddp = -radius * rate * rate * e;
      c.dddp = -radius * rate * rate * rate * e_perp;
      break;
    }
    case MotionPatternKind::FigureEight: {
      const double a = params_.half_length_m, w = params_.half_width_m;
      const double s1 = std::sin(ph), c1 = std::cos(ph);
      const double s2 = std::sin(2 * ph), c2 = std::cos(2 * ph);
      c.p = {a * s1, w * s2};
      c.dp = rate * Eigen::Vector2d(a * c1, 2 * w * c2);
      c.ddp = rate * rate * Eigen::Vector2d(-a * s1, -4 * w * s2);
      c.dddp = rate * rate * rate * Eigen::Vector2d(-a * c1, -8 * w * c2);
      break;
    }
    case MotionPatternKind::Star: {
      // p = r e(ph); derivatives w.r.t. ph by the product rule with e' = e_perp, e'' = -e.
      const double radius = params_.radius_m, depth = params_.star_depth;
      const double n = params_.star_points;
      const double cn = std::cos(n * ph), sn = std::sin(n * ph);
      const double r0 = radius * (1 + depth * cn);
      const double r1 = -radius * depth * n * sn;
      const double r2 = -radius * depth * n * n * cn;
      const double r3 = radius * depth * n * n * n * sn;
      const Eigen::Vector2d e(std::cos(ph), std::sin(ph));
      const Eigen::Vector2d e_perp(-e.y(), e.x());
      c.p = r0 * e;
      c.dp = rate * (r1 * e + r0 * e_perp);
      c.ddp = rate * rate * ((r2 - r0) * e + 2 * r1 * e_perp);
      c.dddp = rate * rate * rate * ((r3 - 3 * r1) * e + (3 * r2 - r0) * e_perp);
      break;
    }
    case MotionPatternKind::SCurve: {
      const double k = model::kTwoPi / params_.wavelength_m, w = params_.half_width_m, u = rate;
      const double th = k * u * t_s + params_.phase_rad;
      const double ku = k * u;
      c.p = {u * t_s, w * std::sin(th)};
      c.dp = {u, w * ku * std::cos(th)};
      c.ddp = {0.0, -w * ku * ku * std::sin(th)};
      c.dddp = {0.0, -w * ku * ku * ku * std::cos(th)};
      break;
    }
    case MotionPatternKind::BackAndForth: {
      const double l = params_.half_length_m;
      c.p = {l * std::sin(ph), 0.0};
      c.dp = {l * rate * std::cos(ph), 0.0};
      c.ddp = {-l * rate * rate * std::sin(ph), 0.0};
      c.dddp = {-l * rate * rate * rate * std::cos(ph), 0.0};
      break;
    }
  }
  return c;
}

UgvKinematics UgvMotionPattern::at(double t_s) const {
  const LocalCurve local = local_curve(t_s);
  const double rotation = params_.orientation_rad;
  UgvKinematics k;
  k.position_m = params_.origin_m + rotate(local.p, rotation);
  k.velocity_m_s = rotate(local.dp, rotation);
  k.acceleration_m_s2 = rotate(local.ddp, rotation);
  if (!heading_follows_velocity()) {
    k.yaw_rad = rotation;
    return k;
  }
  // Heading of the velocity, psi = atan2(y', x'); its rate is the signed curvature times
  // the speed, psi' = (x' y'' - y' x'') / |p'|^2, and psi'' follows by the quotient rule.
  // Rotation-invariant, so computed in the local frame. |p'| > 0 for every pattern here.
  const double speed_sq = local.dp.squaredNorm();
  const double turn = cross2(local.dp, local.ddp);
  const double turn_rate = cross2(local.dp, local.dddp);
  const double speed_sq_rate = 2.0 * local.dp.dot(local.ddp);
  k.yaw_rad = std::atan2(k.velocity_m_s.y(), k.velocity_m_s.x());
  k.yaw_rate_rad_s = turn / speed_sq;
  k.yaw_acceleration_rad_s2 = (turn_rate * speed_sq - turn * speed_sq_rate) / (speed_sq * speed_sq);
  return k;
}

}  // namespace cover::sim
