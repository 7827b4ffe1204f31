#pragma once

#include <Eigen/Core>
#include <vector>

#include "cover/planner/banded_system.hpp"
#include "cover/planner/trajectory.hpp"

namespace cover::planner {

// MINCO for minimum jerk (Wang et al. 2022; s = 3, quintic pieces). Given fixed start and
// end position/velocity/acceleration, M durations T and M-1 intermediate waypoints q, the
// jerk-optimal coefficients c solve a banded linear system A(T) c = b(q) in O(M). Any cost
// K(c, T) then gets its gradient w.r.t. (q, T) through one adjoint solve A^T G = dK/dc:
//   dK/dq_i = G(row of q_i),   dK/dT_i = partial dK/dT_i - G^T (dA/dT_i) c.
// All buffers are sized once by set_conditions(); the per-evaluation calls do not allocate.
class MinimumJerkMinco {
 public:
  using Coefficients = Eigen::Matrix<double, Eigen::Dynamic, 3>;  // 6M x 3, row k of piece i
                                                                  // (row 6i+k) multiplies s^k
  // Columns of the 3x3 matrices: position, velocity, acceleration.
  void set_conditions(const Eigen::Matrix3d& head_pva, const Eigen::Matrix3d& tail_pva, int pieces);
  // waypoints: 3 x (M-1); durations: M, all > 0. Computes the coefficients.
  void set_parameters(const Eigen::Matrix3Xd& waypoints, const Eigen::VectorXd& durations);

  int pieces() const { return pieces_; }
  const Coefficients& coefficients() const { return coefficients_; }
  const Eigen::VectorXd& durations() const { return durations_; }

  // Sum over pieces of integral ||jerk||^2 dt, and its partial gradients (added in).
  double jerk_energy() const;
  void add_jerk_energy_gradient(Coefficients& gradient_by_coefficients,
                                Eigen::VectorXd& gradient_by_durations) const;

  // Turns partial gradients (by c, by T) into total gradients by waypoints and durations.
  // gradient_by_coefficients is overwritten (used as the adjoint buffer).
  void propagate_gradient(Coefficients& gradient_by_coefficients,
                          const Eigen::VectorXd& partial_gradient_by_durations,
                          Eigen::Matrix3Xd& gradient_by_waypoints,
                          Eigen::VectorXd& gradient_by_durations) const;

  Trajectory trajectory() const;
  // The same into `out`, reusing its storage (no allocation once it held M pieces).
  void write_trajectory(Trajectory& out);

 private:
  void fill_matrix();

  int pieces_ = 0;
  Eigen::Matrix3d head_pva_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d tail_pva_ = Eigen::Matrix3d::Zero();
  Eigen::VectorXd durations_;
  BandedSystem system_;
  Coefficients coefficients_;
  std::vector<TrajectoryPiece> pieces_buffer_;  // M pieces, for write_trajectory
};

}  // namespace cover::planner
