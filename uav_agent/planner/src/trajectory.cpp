#include "cover/planner/trajectory.hpp"

#include <algorithm>
#include <cmath>

namespace cover::planner {

namespace {

// d^order/ds^order of s^k is k!/(k-order)! s^(k-order): evaluated by Horner's rule.
Eigen::Vector3d evaluate_piece(const TrajectoryPiece& piece, double s, int order) {
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  for (int k = 5; k >= order; --k) {
    double falling_factorial = 1.0;
    for (int m = 0; m < order; ++m) falling_factorial *= (k - m);
    value = value * s + falling_factorial * piece.coefficients.row(k).transpose();
  }
  return value;
}

}  // namespace

// One zero piece of zero duration: holds the origin.
Trajectory::Trajectory() : Trajectory(std::vector<TrajectoryPiece>(1)) {}

Trajectory::Trajectory(std::vector<TrajectoryPiece> pieces) : pieces_(std::move(pieces)) {
  if (pieces_.empty()) pieces_.push_back(TrajectoryPiece{});
  piece_start_s_.reserve(pieces_.size());
  for (const auto& piece : pieces_) {
    piece_start_s_.push_back(duration_s_);
    duration_s_ += piece.duration_s;
  }
}

Trajectory Trajectory::hold(const Eigen::Vector3d& point_m) {
  TrajectoryPiece piece;
  piece.coefficients.row(0) = point_m.transpose();
  return Trajectory(std::vector<TrajectoryPiece>{piece});
}

void Trajectory::assign(const TrajectoryPiece* pieces, int count) {
  pieces_.assign(pieces, pieces + std::max(count, 0));
  if (pieces_.empty()) pieces_.push_back(TrajectoryPiece{});
  piece_start_s_.clear();
  duration_s_ = 0.0;
  for (const auto& piece : pieces_) {
    piece_start_s_.push_back(duration_s_);
    duration_s_ += piece.duration_s;
  }
}

void Trajectory::assign_hold(const Eigen::Vector3d& point_m) {
  TrajectoryPiece piece;
  piece.coefficients.row(0) = point_m.transpose();
  assign(&piece, 1);
}

void Trajectory::reserve(int pieces) {
  const auto count = static_cast<std::size_t>(std::max(pieces, 1));
  pieces_.reserve(count);
  piece_start_s_.reserve(count);
}

Eigen::Vector3d Trajectory::derivative(double t_s, int order) const {
  if (order < 0 || order > 5) return Eigen::Vector3d::Zero();
  const double t = std::isnan(t_s) ? 0.0 : std::clamp(t_s, 0.0, duration_s_);
  // Last piece whose start is <= t; few pieces, so a binary search is plenty.
  const auto it = std::upper_bound(piece_start_s_.begin(), piece_start_s_.end(), t);
  const auto index = static_cast<std::size_t>(
      std::max<std::ptrdiff_t>(0, std::distance(piece_start_s_.begin(), it) - 1));
  const auto& piece = pieces_[index];
  const double s = std::clamp(t - piece_start_s_[index], 0.0, piece.duration_s);
  return evaluate_piece(piece, s, order);
}

bool Trajectory::is_finite() const {
  return std::all_of(pieces_.begin(), pieces_.end(), [](const TrajectoryPiece& piece) {
    return std::isfinite(piece.duration_s) && piece.duration_s >= 0.0 &&
           piece.coefficients.allFinite();
  });
}

}  // namespace cover::planner
