#include "cover/sampc/qp_riccati.hpp"

#include <algorithm>
#include <cmath>

// Every product below is written as lazyProduct: for these 10x10-ish fixed sizes Eigen's
// default picks its blocked GEMM (packing and all), several times slower than the
// unrolled coefficient-based kernel.

namespace cover::sampc {
namespace {

// An input this close to a bound counts as on it (the iterates are projected exactly,
// so this only absorbs rounding).
constexpr double kOnBound = 1e-10;
// A bound-held input is released only when its gradient points inside by more than this.
constexpr double kGradientTolerance = 1e-9;
// Projected Armijo search: sufficient decrease fraction and step halvings.
constexpr double kArmijo = 1e-4;
constexpr int kMaxHalvings = 30;

}  // namespace

void RiccatiQp::factorize(const ActiveSet& active) {
  factored_active_ = active;
  P_[horizon_] = nodes[horizon_].Q;
  MatrixXX PA, Q_bar;
  MatrixXU PB;
  for (int k = horizon_ - 1; k >= 0; --k) {
    const QpNode& n = nodes[k];
    const MatrixXX& P = P_[k + 1];
    // A's attitude rows are zero in the position and velocity columns (QpNode): PA's
    // translational columns skip them. (A'PA's translational rows could too, but a dot
    // product of 6 instead of 10 terms rounds differently and moves flight results.)
    PA.leftCols<kTranslational>().noalias() = P.leftCols<kTranslational>().lazyProduct(
        n.A.topLeftCorner<kTranslational, kTranslational>());
    PA.rightCols<kAttitude>().noalias() = P.lazyProduct(n.A.rightCols<kAttitude>());
    PB.noalias() = P.lazyProduct(n.B);
    MatrixUU& R_bar = r_bar_[k];
    MatrixUX& S_bar = s_bar_[k];
    R_bar = n.R;
    R_bar.noalias() += n.B.transpose().lazyProduct(PB);
    S_bar = n.S;
    S_bar.noalias() += n.B.transpose().lazyProduct(PA);
    Q_bar = n.Q;
    Q_bar.noalias() += n.A.transpose().lazyProduct(PA);

    // Bound-held inputs leave the stage problem: identity rows/columns in M, no feedback.
    MatrixUU M = R_bar;
    MatrixUX S_free = S_bar;
    for (int i = 0; i < kNu; ++i) {
      if (active[k][i] == BoundState::Free) continue;
      M.row(i).setZero();
      M.col(i).setZero();
      M(i, i) = 1.0;
      S_free.row(i).setZero();
    }
    // M = R + B'PB (free block) is 4x4 SPD and well conditioned (R > 0): Eigen's closed-form
    // 4x4 inverse is exact enough and much faster than a Cholesky solve with 10 columns.
    MatrixUU& M_inv = free_inverse_[k];
    M_inv = M.inverse();
    MatrixUX& K = K_[k];
    K.noalias() = -M_inv.lazyProduct(S_free);

    // Value of the stage under du = K dx: Q_bar + S'K + K'S + K'R K, where K'(S + R K) = 0
    // for any active set (free rows: the stationarity that defines K; held rows: K is 0
    // there), leaving the textbook Q_bar + S'K = Q_bar - S' M^-1 S.
    MatrixXX& P_k = P_[k];
    P_k = Q_bar;
    P_k.noalias() += S_bar.transpose().lazyProduct(K);
    P_k = (0.5 * (P_k + P_k.transpose())).eval();
  }
}

void RiccatiQp::newton_point(const VectorX& dx0) {
  // Vector part of the recursion: p_k and the feedforward k_k, with the bound-held inputs
  // at their current values.
  std::array<VectorU, kMaxHorizon> feedforward;
  VectorX p = nodes[horizon_].q;
  for (int k = horizon_ - 1; k >= 0; --k) {
    const QpNode& n = nodes[k];
    VectorX p_next = p;
    p_next.noalias() += P_[k + 1].lazyProduct(n.c);
    VectorU r_bar = n.r;
    r_bar.noalias() += n.B.transpose().lazyProduct(p_next);
    VectorU r_free = r_bar;
    for (int i = 0; i < kNu; ++i) {
      if (factored_active_[k][i] == BoundState::Free) continue;
      r_free += r_bar_[k].col(i) * du_[k](i);
    }
    for (int i = 0; i < kNu; ++i) {
      if (factored_active_[k][i] != BoundState::Free) r_free(i) = -du_[k](i);
    }
    VectorU& kk = feedforward[k];
    kk.noalias() = -free_inverse_[k].lazyProduct(r_free);
    // As for P: K'(r_bar + R_bar k) vanishes, so p = q_bar + S'k.
    VectorX p_k = n.q;
    p_k.noalias() += n.A.transpose().lazyProduct(p_next);
    p_k.noalias() += s_bar_[k].transpose().lazyProduct(kk);
    p = p_k;
  }
  new_dx_[0] = dx0;
  for (int k = 0; k < horizon_; ++k) {
    const QpNode& n = nodes[k];
    new_du_[k] = feedforward[k];
    new_du_[k].noalias() += K_[k].lazyProduct(new_dx_[k]);
    new_dx_[k + 1] = n.c;
    new_dx_[k + 1].noalias() += n.A.lazyProduct(new_dx_[k]);
    new_dx_[k + 1].noalias() += n.B.lazyProduct(new_du_[k]);
  }
}

void RiccatiQp::simulate(const VectorX& dx0, const std::array<VectorU, kMaxHorizon>& du,
                         std::array<VectorX, kMaxHorizon + 1>& dx) const {
  dx[0] = dx0;
  for (int k = 0; k < horizon_; ++k) {
    dx[k + 1] = nodes[k].c;
    dx[k + 1].noalias() += nodes[k].A.lazyProduct(dx[k]);
    dx[k + 1].noalias() += nodes[k].B.lazyProduct(du[k]);
  }
}

double RiccatiQp::objective(const std::array<VectorU, kMaxHorizon>& du,
                            const std::array<VectorX, kMaxHorizon + 1>& dx) const {
  double value = 0.0;
  for (int k = 0; k < horizon_; ++k) {
    const QpNode& n = nodes[k];
    value += 0.5 * dx[k].dot(n.Q * dx[k]) + du[k].dot(n.S * dx[k]) + 0.5 * du[k].dot(n.R * du[k]) +
             n.q.dot(dx[k]) + n.r.dot(du[k]);
  }
  const QpNode& t = nodes[horizon_];
  return value + 0.5 * dx[horizon_].dot(t.Q * dx[horizon_]) + t.q.dot(dx[horizon_]);
}

double RiccatiQp::objective() const {
  return objective(du_, dx_);
}

void RiccatiQp::compute_gradient() {
  // Adjoint sweep: lambda_k = d objective / d dx_k along the dynamics.
  VectorX lambda = nodes[horizon_].q;
  lambda.noalias() += nodes[horizon_].Q.lazyProduct(dx_[horizon_]);
  for (int k = horizon_ - 1; k >= 0; --k) {
    const QpNode& n = nodes[k];
    VectorU& g = gradient_[k];
    g = n.r;
    g.noalias() += n.R.lazyProduct(du_[k]);
    g.noalias() += n.S.lazyProduct(dx_[k]);
    g.noalias() += n.B.transpose().lazyProduct(lambda);
    VectorX next = n.q;
    next.noalias() += n.Q.lazyProduct(dx_[k]);
    next.noalias() += n.S.transpose().lazyProduct(du_[k]);
    next.noalias() += n.A.transpose().lazyProduct(lambda);
    lambda = next;
  }
}

void RiccatiQp::identify_active_set(ActiveSet& active) const {
  for (int k = 0; k < horizon_; ++k) {
    for (int i = 0; i < kNu; ++i) {
      const double u = du_[k](i), g = gradient_[k](i);
      BoundState state = BoundState::Free;
      if (u <= nodes[k].lower(i) + kOnBound && g > kGradientTolerance) state = BoundState::AtLower;
      if (u >= nodes[k].upper(i) - kOnBound && g < -kGradientTolerance) state = BoundState::AtUpper;
      active[k][i] = state;
    }
  }
}

bool RiccatiQp::off_every_bound(const std::array<VectorU, kMaxHorizon>& du) const {
  for (int k = 0; k < horizon_; ++k) {
    if ((du[k].array() <= nodes[k].lower.array() + kOnBound).any() ||
        (du[k].array() >= nodes[k].upper.array() - kOnBound).any()) {
      return false;
    }
  }
  return true;
}

bool RiccatiQp::within_bounds(const std::array<VectorU, kMaxHorizon>& du) const {
  for (int k = 0; k < horizon_; ++k) {
    if ((du[k].array() < nodes[k].lower.array() - kOnBound).any() ||
        (du[k].array() > nodes[k].upper.array() + kOnBound).any()) {
      return false;
    }
  }
  return true;
}

void RiccatiQp::prepare(int horizon) {
  horizon_ = horizon;
  for (int k = 0; k < horizon_; ++k) du_[k].setZero();
  simulate(VectorX::Zero(), du_, dx_);
  ActiveSet active{};
  // An input can only be held where it sits on a bound: with none there (the common case)
  // every input is free whatever the gradient, which then need not be computed.
  if (!off_every_bound(du_)) {
    compute_gradient();
    identify_active_set(active);
  }
  factorize(active);
}

QpResult RiccatiQp::solve_prepared(const VectorX& dx0, int max_iterations) {
  QpResult result;
  // Start from the current plan (du = 0), feasible by construction.
  for (int k = 0; k < horizon_; ++k) du_[k].setZero();
  simulate(dx0, du_, dx_);
  // The gradient decides only which inputs on a bound are held, and the Armijo search's
  // prediction: off every bound (the common case) it is not needed at all.
  bool gradient_current = false;
  const auto update_gradient = [&] {
    if (!gradient_current) compute_gradient();
    gradient_current = true;
  };
  const auto find_active_set = [&](ActiveSet& active) {
    if (off_every_bound(du_)) {
      active = ActiveSet{};
      return;
    }
    update_gradient();
    identify_active_set(active);
  };
  ActiveSet active{};
  while (result.iterations < max_iterations) {
    ++result.iterations;
    find_active_set(active);
    if (active != factored_active_) {
      factorize(active);
      ++result.factorizations;
    }
    newton_point(dx0);
    if (within_bounds(new_du_)) {
      // The exact minimiser on this face is feasible: optimal unless a held input wants out.
      du_ = new_du_;
      dx_ = new_dx_;
      gradient_current = false;
      find_active_set(active);
      if (active == factored_active_) {
        result.converged = true;
        return result;
      }
      continue;
    }
    // Projected Armijo search along the Newton direction.
    update_gradient();
    const double current = objective(du_, dx_);
    double step = 1.0;
    for (int halving = 0; halving <= kMaxHalvings; ++halving, step *= 0.5) {
      double predicted = 0.0;
      for (int k = 0; k < horizon_; ++k) {
        trial_du_[k] = (du_[k] + step * (new_du_[k] - du_[k]))
                           .cwiseMax(nodes[k].lower)
                           .cwiseMin(nodes[k].upper);
        predicted += gradient_[k].dot(trial_du_[k] - du_[k]);
      }
      simulate(dx0, trial_du_, trial_dx_);
      if (objective(trial_du_, trial_dx_) <= current + kArmijo * predicted) break;
    }
    du_ = trial_du_;
    dx_ = trial_dx_;
    gradient_current = false;
  }
  return result;
}

QpResult RiccatiQp::solve(int horizon, const VectorX& dx0, int max_iterations) {
  prepare(horizon);
  return solve_prepared(dx0, max_iterations);
}

}  // namespace cover::sampc
