#include "cover/planner/banded_system.hpp"

#include <algorithm>

namespace cover::planner {

void BandedSystem::resize(int size, int lower_bandwidth, int upper_bandwidth) {
  size_ = size;
  lower_ = lower_bandwidth;
  upper_ = upper_bandwidth;
  band_.assign(static_cast<std::size_t>((lower_ + upper_ + 1) * size_), 0.0);
}

void BandedSystem::set_zero() {
  std::fill(band_.begin(), band_.end(), 0.0);
}

void BandedSystem::factorize() {
  BandedSystem& a = *this;
  for (int k = 0; k < size_ - 1; ++k) {
    const int last_row = std::min(k + lower_, size_ - 1);
    const double pivot = a(k, k);
    for (int i = k + 1; i <= last_row; ++i) {
      if (a(i, k) != 0.0) a(i, k) /= pivot;
    }
    const int last_col = std::min(k + upper_, size_ - 1);
    for (int j = k + 1; j <= last_col; ++j) {
      const double factor = a(k, j);
      if (factor == 0.0) continue;
      for (int i = k + 1; i <= last_row; ++i) {
        if (a(i, k) != 0.0) a(i, j) -= a(i, k) * factor;
      }
    }
  }
}

void BandedSystem::solve(Eigen::Matrix<double, Eigen::Dynamic, 3>& rhs) const {
  const BandedSystem& a = *this;
  for (int j = 0; j < size_; ++j) {  // L y = b
    const int last_row = std::min(j + lower_, size_ - 1);
    for (int i = j + 1; i <= last_row; ++i) {
      if (a(i, j) != 0.0) rhs.row(i) -= a(i, j) * rhs.row(j);
    }
  }
  for (int j = size_ - 1; j >= 0; --j) {  // U x = y
    rhs.row(j) /= a(j, j);
    const int first_row = std::max(0, j - upper_);
    for (int i = first_row; i < j; ++i) {
      if (a(i, j) != 0.0) rhs.row(i) -= a(i, j) * rhs.row(j);
    }
  }
}

void BandedSystem::solve_transposed(Eigen::Matrix<double, Eigen::Dynamic, 3>& rhs) const {
  const BandedSystem& a = *this;
  for (int j = 0; j < size_; ++j) {  // U^T y = b
    rhs.row(j) /= a(j, j);
    const int last_row = std::min(j + upper_, size_ - 1);
    for (int i = j + 1; i <= last_row; ++i) {
      if (a(j, i) != 0.0) rhs.row(i) -= a(j, i) * rhs.row(j);
    }
  }
  for (int j = size_ - 1; j >= 0; --j) {  // L^T x = y
    const int first_row = std::max(0, j - lower_);
    for (int i = first_row; i < j; ++i) {
      if (a(j, i) != 0.0) rhs.row(i) -= a(j, i) * rhs.row(j);
    }
  }
}

}  // namespace cover::planner
