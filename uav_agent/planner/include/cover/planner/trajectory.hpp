#pragma once

#include <Eigen/Core>
#include <vector>

namespace cover::planner {

// One quintic piece: p(s) = sum_k coefficients.row(k) * s^k for local time s in [0, duration].
struct TrajectoryPiece {
  double duration_s = 0.0;
  Eigen::Matrix<double, 6, 3> coefficients = Eigen::Matrix<double, 6, 3>::Zero();
};

// Piecewise-quintic reference z(t) over [0, duration_s()]. Queries clamp t to that
// interval (a NaN t reads as 0), so a caller past the end gets the goal at rest and can
// never read garbage. The default trajectory holds the origin; hold(p) holds p.
class Trajectory {
 public:
  Trajectory();
  explicit Trajectory(std::vector<TrajectoryPiece> pieces);
  static Trajectory hold(const Eigen::Vector3d& point_m);

  // Replace the pieces in place (count >= 1), or hold a point: the storage is reused, so a
  // planner refilling the same trajectory every stage allocates nothing once it has held
  // as many pieces.
  void assign(const TrajectoryPiece* pieces, int count);
  void assign_hold(const Eigen::Vector3d& point_m);
  // Room for `pieces` pieces: assign() of at most that many allocates nothing from now on
  // (the storage moves with the trajectory when it is swapped).
  void reserve(int pieces);

  double duration_s() const { return duration_s_; }
  int piece_count() const { return static_cast<int>(pieces_.size()); }
  const std::vector<TrajectoryPiece>& pieces() const { return pieces_; }

  Eigen::Vector3d position(double t_s) const { return derivative(t_s, 0); }
  Eigen::Vector3d velocity(double t_s) const { return derivative(t_s, 1); }
  Eigen::Vector3d acceleration(double t_s) const { return derivative(t_s, 2); }
  Eigen::Vector3d jerk(double t_s) const { return derivative(t_s, 3); }
  // order 0..5; higher orders are zero.
  Eigen::Vector3d derivative(double t_s, int order) const;

  // True when every coefficient and duration is finite (durations also non-negative).
  bool is_finite() const;

 private:
  std::vector<TrajectoryPiece> pieces_;
  std::vector<double> piece_start_s_;
  double duration_s_ = 0.0;
};

}  // namespace cover::planner
