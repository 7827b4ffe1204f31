#include "cover/planner/minco.hpp"

#include <vector>

namespace cover::planner {

// Row layout of A (6M rows), following the optimality conditions of minimum jerk:
//   rows 0..2            start position, velocity, acceleration of piece 0
//   rows 6i+3, 6i+4      jerk and snap continuity between pieces i and i+1
//   row  6i+5            end position of piece i equals waypoint q_i
//   rows 6i+6..6i+8      position, velocity, acceleration continuity
//   rows 6M-3..6M-1      end position, velocity, acceleration of the last piece
void MinimumJerkMinco::set_conditions(const Eigen::Matrix3d& head_pva,
                                      const Eigen::Matrix3d& tail_pva, int pieces) {
  pieces_ = pieces;
  head_pva_ = head_pva;
  tail_pva_ = tail_pva;
  durations_.setOnes(pieces);
  system_.resize(6 * pieces, 6, 6);
  coefficients_.setZero(6 * pieces, 3);
  pieces_buffer_.resize(static_cast<std::size_t>(pieces));
}

void MinimumJerkMinco::fill_matrix() {
  BandedSystem& a = system_;
  a.set_zero();
  a(0, 0) = 1.0;
  a(1, 1) = 1.0;
  a(2, 2) = 2.0;
  for (int i = 0; i < pieces_ - 1; ++i) {
    const double t1 = durations_(i), t2 = t1 * t1, t3 = t2 * t1, t4 = t3 * t1, t5 = t4 * t1;
    const int r = 6 * i;
    a(r + 3, r + 3) = 6.0;
    a(r + 3, r + 4) = 24.0 * t1;
    a(r + 3, r + 5) = 60.0 * t2;
    a(r + 3, r + 9) = -6.0;
    a(r + 4, r + 4) = 24.0;
    a(r + 4, r + 5) = 120.0 * t1;
    a(r + 4, r + 10) = -24.0;
    const double position_row[6] = {1.0, t1, t2, t3, t4, t5};
    for (int k = 0; k < 6; ++k) {
      a(r + 5, r + k) = position_row[k];
      a(r + 6, r + k) = position_row[k];
    }
    a(r + 6, r + 6) = -1.0;
    a(r + 7, r + 1) = 1.0;
    a(r + 7, r + 2) = 2.0 * t1;
    a(r + 7, r + 3) = 3.0 * t2;
    a(r + 7, r + 4) = 4.0 * t3;
    a(r + 7, r + 5) = 5.0 * t4;
    a(r + 7, r + 7) = -1.0;
    a(r + 8, r + 2) = 2.0;
    a(r + 8, r + 3) = 6.0 * t1;
    a(r + 8, r + 4) = 12.0 * t2;
    a(r + 8, r + 5) = 20.0 * t3;
    a(r + 8, r + 8) = -2.0;
  }
  const int r = 6 * (pieces_ - 1);
  const double t1 = durations_(pieces_ - 1), t2 = t1 * t1, t3 = t2 * t1, t4 = t3 * t1, t5 = t4 * t1;
  const double end_rows[3][6] = {{1.0, t1, t2, t3, t4, t5},
                                 {0.0, 1.0, 2.0 * t1, 3.0 * t2, 4.0 * t3, 5.0 * t4},
                                 {0.0, 0.0, 2.0, 6.0 * t1, 12.0 * t2, 20.0 * t3}};
  for (int row = 0; row < 3; ++row) {
    for (int k = 0; k < 6; ++k) {
      if (end_rows[row][k] != 0.0) a(r + 3 + row, r + k) = end_rows[row][k];
    }
  }
}

void MinimumJerkMinco::set_parameters(const Eigen::Matrix3Xd& waypoints,
                                      const Eigen::VectorXd& durations) {
  durations_ = durations;
  fill_matrix();
  coefficients_.setZero();
  coefficients_.topRows<3>() = head_pva_.transpose();
  for (int i = 0; i < pieces_ - 1; ++i) coefficients_.row(6 * i + 5) = waypoints.col(i).transpose();
  coefficients_.bottomRows<3>() = tail_pva_.transpose();
  system_.factorize();
  system_.solve(coefficients_);
}

// integral_0^T ||6 c3 + 24 c4 s + 60 c5 s^2||^2 ds, expanded per pair of coefficients.
double MinimumJerkMinco::jerk_energy() const {
  double energy = 0.0;
  for (int i = 0; i < pieces_; ++i) {
    const double t1 = durations_(i), t2 = t1 * t1, t3 = t2 * t1, t4 = t3 * t1, t5 = t4 * t1;
    const auto c3 = coefficients_.row(6 * i + 3), c4 = coefficients_.row(6 * i + 4),
               c5 = coefficients_.row(6 * i + 5);
    energy += 36.0 * c3.squaredNorm() * t1 + 144.0 * c3.dot(c4) * t2 +
              192.0 * c4.squaredNorm() * t3 + 240.0 * c3.dot(c5) * t3 + 720.0 * c4.dot(c5) * t4 +
              720.0 * c5.squaredNorm() * t5;
  }
  return energy;
}

void MinimumJerkMinco::add_jerk_energy_gradient(Coefficients& gradient_by_coefficients,
                                                Eigen::VectorXd& gradient_by_durations) const {
  for (int i = 0; i < pieces_; ++i) {
    const double t1 = durations_(i), t2 = t1 * t1, t3 = t2 * t1, t4 = t3 * t1, t5 = t4 * t1;
    const auto c3 = coefficients_.row(6 * i + 3), c4 = coefficients_.row(6 * i + 4),
               c5 = coefficients_.row(6 * i + 5);
    gradient_by_coefficients.row(6 * i + 3) += 72.0 * c3 * t1 + 144.0 * c4 * t2 + 240.0 * c5 * t3;
    gradient_by_coefficients.row(6 * i + 4) += 144.0 * c3 * t2 + 384.0 * c4 * t3 + 720.0 * c5 * t4;
    gradient_by_coefficients.row(6 * i + 5) += 240.0 * c3 * t3 + 720.0 * c4 * t4 + 1440.0 * c5 * t5;
    gradient_by_durations(i) += 36.0 * c3.squaredNorm() + 288.0 * c3.dot(c4) * t1 +
                                576.0 * c4.squaredNorm() * t2 + 720.0 * c3.dot(c5) * t2 +
                                2880.0 * c4.dot(c5) * t3 + 3600.0 * c5.squaredNorm() * t4;
  }
}

void MinimumJerkMinco::propagate_gradient(Coefficients& gradient_by_coefficients,
                                          const Eigen::VectorXd& partial_gradient_by_durations,
                                          Eigen::Matrix3Xd& gradient_by_waypoints,
                                          Eigen::VectorXd& gradient_by_durations) const {
  Coefficients& adjoint = gradient_by_coefficients;
  system_.solve_transposed(adjoint);
  for (int i = 0; i < pieces_ - 1; ++i) {
    gradient_by_waypoints.col(i) = adjoint.row(6 * i + 5).transpose();
  }
  // d(row)/dT_i times c: the time derivative of each constrained quantity at s = T_i.
  for (int i = 0; i < pieces_; ++i) {
    const double t1 = durations_(i), t2 = t1 * t1, t3 = t2 * t1, t4 = t3 * t1;
    const auto c = coefficients_.middleRows<6>(6 * i);
    const Eigen::RowVector3d velocity = c.row(1) + 2.0 * t1 * c.row(2) + 3.0 * t2 * c.row(3) +
                                        4.0 * t3 * c.row(4) + 5.0 * t4 * c.row(5);
    const Eigen::RowVector3d acceleration =
        2.0 * c.row(2) + 6.0 * t1 * c.row(3) + 12.0 * t2 * c.row(4) + 20.0 * t3 * c.row(5);
    const Eigen::RowVector3d jerk = 6.0 * c.row(3) + 24.0 * t1 * c.row(4) + 60.0 * t2 * c.row(5);
    double dot = 0.0;
    if (i < pieces_ - 1) {
      const Eigen::RowVector3d snap = 24.0 * c.row(4) + 120.0 * t1 * c.row(5);
      const Eigen::RowVector3d crackle = 120.0 * c.row(5);
      const auto g = adjoint.middleRows<6>(6 * i + 3);
      dot = g.row(0).dot(snap) + g.row(1).dot(crackle) + g.row(2).dot(velocity) +
            g.row(3).dot(velocity) + g.row(4).dot(acceleration) + g.row(5).dot(jerk);
    } else {
      const auto g = adjoint.bottomRows<3>();
      dot = g.row(0).dot(velocity) + g.row(1).dot(acceleration) + g.row(2).dot(jerk);
    }
    gradient_by_durations(i) = partial_gradient_by_durations(i) - dot;
  }
}

Trajectory MinimumJerkMinco::trajectory() const {
  std::vector<TrajectoryPiece> pieces(static_cast<std::size_t>(pieces_));
  for (int i = 0; i < pieces_; ++i) {
    pieces[static_cast<std::size_t>(i)].duration_s = durations_(i);
    pieces[static_cast<std::size_t>(i)].coefficients = coefficients_.middleRows<6>(6 * i);
  }
  return Trajectory(std::move(pieces));
}

}  // namespace cover::planner

namespace cover::planner {

void MinimumJerkMinco::write_trajectory(Trajectory& out) {
  for (int i = 0; i < pieces_; ++i) {
    pieces_buffer_[static_cast<std::size_t>(i)].duration_s = durations_(i);
    pieces_buffer_[static_cast<std::size_t>(i)].coefficients = coefficients_.middleRows<6>(6 * i);
  }
  out.assign(pieces_buffer_.data(), pieces_);
}

}  // namespace cover::planner
