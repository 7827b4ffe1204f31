#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <array>
#include <cstdint>

#include "cover/sampc/sampc_params.hpp"
#include "cover/vocabulary/state.hpp"

namespace cover::sampc {

inline constexpr int kNx = model::kUavStateSize;  // decision states per node (p, v, q)
inline constexpr int kNu = model::kInputSize;     // inputs per node

using VectorX = Eigen::Matrix<double, kNx, 1>;
using VectorU = Eigen::Matrix<double, kNu, 1>;
using MatrixXX = Eigen::Matrix<double, kNx, kNx>;
using MatrixXU = Eigen::Matrix<double, kNx, kNu>;
using MatrixUX = Eigen::Matrix<double, kNu, kNx>;
using MatrixUU = Eigen::Matrix<double, kNu, kNu>;
// The state's translational part (p, v) and its attitude part (q).
inline constexpr int kTranslational = model::idx::kQuaternion;
inline constexpr int kAttitude = kNx - kTranslational;

// Data of one node k of the stage-structured QP
//   min  sum_k 1/2 [dx;du]' [Q S'; S R] [dx;du] + q'dx + r'du   (+ terminal 1/2 dx'Q dx + q'dx)
//   s.t. dx_{k+1} = A dx_k + B du_k + c,   dx_0 given,   lower <= du_k <= upper.
// The terminal node uses only Q and q. A's attitude rows must be zero in the translational
// columns (the attitude's dynamics involve the attitude and the rates only): the
// factorisation skips that block.
struct QpNode {
  MatrixXX A, Q;
  MatrixXU B;
  MatrixUX S;
  MatrixUU R;
  VectorX c, q;
  VectorU r, lower, upper;
};

// Which bound an input component is held at in the current active set.
enum class BoundState : std::uint8_t { Free, AtLower, AtUpper };

struct QpResult {
  bool converged = false;  // KKT conditions hold (to rounding) at the returned point
  int iterations = 0;      // projected-Newton iterations
  int factorizations = 0;  // Riccati matrix recursions (one per active-set change)
};

// Structured QP solver: projected Newton (Bertsekas 1982) on the input boxes, each
// Newton step computed by a Riccati recursion over the horizon with the bound-held inputs
// removed. O(N nx^3), fixed-size Eigen types, no heap allocation.
//  - The iterate stays feasible (projection) and the cost decreases monotonically
//    (projected Armijo search), so even an iteration cap leaves a feasible, improved point;
//    and the method terminates exactly once the active set is right (typically 1-3
//    iterations; one when nothing saturates).
//  - The recursion is split: the matrix part (P, K; the expensive O(nx^3) work) depends
//    only on the active set, the vector part (p, k) on the linear terms and dx_0. prepare()
//    does the matrix part for the active set expected at dx_0 = 0, before the measurement;
//    solve_prepared() then costs a few matrix-vector sweeps unless the active set changes.
class RiccatiQp {
 public:
  // Filled by the caller for k = 0..horizon (the terminal node's A, B, S, R, c are unused).
  // Bounds must contain 0 (the current plan is feasible), which SAMPC guarantees.
  std::array<QpNode, kMaxHorizon + 1> nodes;

  // Preparation phase: guesses the active set at dx_0 = 0 and factorises for it.
  void prepare(int horizon);
  // Feedback phase: solves for the given dx_0. Requires prepare() after the last change of
  // `nodes`.
  QpResult solve_prepared(const VectorX& dx0, int max_iterations);
  // prepare + solve_prepared.
  QpResult solve(int horizon, const VectorX& dx0, int max_iterations);

  const VectorX& dx(int k) const { return dx_[k]; }
  const VectorU& du(int k) const { return du_[k]; }
  BoundState bound_state(int k, int i) const { return factored_active_[k][i]; }
  // QP objective at the current point.
  double objective() const;

 private:
  using ActiveSet = std::array<std::array<BoundState, kNu>, kMaxHorizon>;

  void factorize(const ActiveSet& active);
  // Newton point on the current face: inputs in the active set held at their values in
  // `du_`, the others optimal. Writes new_du_, new_dx_.
  void newton_point(const VectorX& dx0);
  void simulate(const VectorX& dx0, const std::array<VectorU, kMaxHorizon>& du,
                std::array<VectorX, kMaxHorizon + 1>& dx) const;
  double objective(const std::array<VectorU, kMaxHorizon>& du,
                   const std::array<VectorX, kMaxHorizon + 1>& dx) const;
  void compute_gradient();  // gradient_ = d objective / d du at (du_, dx_)
  void identify_active_set(ActiveSet& active) const;
  bool within_bounds(const std::array<VectorU, kMaxHorizon>& du) const;
  // No input within rounding of either bound (so none can be held).
  bool off_every_bound(const std::array<VectorU, kMaxHorizon>& du) const;

  int horizon_ = 0;
  ActiveSet factored_active_{};
  // Matrix part of the recursion, per node.
  std::array<MatrixXX, kMaxHorizon + 1> P_;
  std::array<MatrixUX, kMaxHorizon> K_;
  std::array<MatrixUU, kMaxHorizon> r_bar_;
  std::array<MatrixUX, kMaxHorizon> s_bar_;
  std::array<MatrixUU, kMaxHorizon> free_inverse_;  // (R + B'PB) on the free inputs, inverted
  // Iterates.
  std::array<VectorX, kMaxHorizon + 1> dx_, new_dx_, trial_dx_;
  std::array<VectorU, kMaxHorizon> du_, new_du_, trial_du_, gradient_;
};

}  // namespace cover::sampc
