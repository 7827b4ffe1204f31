#pragma once

#include <Eigen/Core>
#include <vector>

namespace cover::planner {

// A square banded matrix with in-place LU factorisation WITHOUT pivoting. MINCO's
// matrix is banded (bandwidth 6 for minimum jerk) and its structure keeps the pivots
// away from zero for positive durations, so solving costs O(n) instead of O(n^3).
class BandedSystem {
 public:
  void resize(int size, int lower_bandwidth, int upper_bandwidth);
  void set_zero();
  int size() const { return size_; }

  // Element (row, col); must lie inside the band.
  double& operator()(int row, int col) { return band_[index(row, col)]; }
  double operator()(int row, int col) const { return band_[index(row, col)]; }

  // Replaces the matrix by its L (unit lower) and U factors.
  void factorize();
  // After factorize(): overwrites rhs with A^-1 rhs, or with A^-T rhs (the adjoint).
  void solve(Eigen::Matrix<double, Eigen::Dynamic, 3>& rhs) const;
  void solve_transposed(Eigen::Matrix<double, Eigen::Dynamic, 3>& rhs) const;

 private:
  int index(int row, int col) const { return (row - col + upper_) * size_ + col; }

  int size_ = 0;
  int lower_ = 0;
  int upper_ = 0;
  std::vector<double> band_;
};

}  // namespace cover::planner
