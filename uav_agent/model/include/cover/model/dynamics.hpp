#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cover/vocabulary/state.hpp"
#include "cover/vocabulary/ugv_motion.hpp"

namespace cover::model {

// The non-inertial model of paper eqs. 3-8 as docs/model.md writes them, in UGV frame G_k:
//   p'     = v
//   v'     = -beta x p - 2 Omega x v - Omega x (Omega x p) + R(q) [0, 0, F] - a
//   q'     = 1/2 q (x) [0, w]  -  1/2 [0, Omega] (x) q
//   Omega' = beta,   a' = 0,   beta' = 0
// Two views of the same equations:
//  - the full 19-state model (`dynamics`, `rk4_step`, ...), the paper's form;
//  - the 10-state UAV model with the UGV motion as a parameter (`uav_*`), which is what
//    SAMPC optimises over: a, Omega, beta are not controllable, so keeping them out of the
//    decision vector shrinks every Riccati step from 19x19 to 10x10.
// Both RK4 steps normalise the quaternion afterwards; their Jacobians include that.

using StateMatrix = Eigen::Matrix<double, kStateSize, kStateSize>;
using StateInputMatrix = Eigen::Matrix<double, kStateSize, kInputSize>;
using UavStateMatrix = Eigen::Matrix<double, kUavStateSize, kUavStateSize>;
using UavInputMatrix = Eigen::Matrix<double, kUavStateSize, kInputSize>;

// --- full 19-state model ---------------------------------------------------------------

// Continuous dynamics x' = f(x, u).
State dynamics(const State& x, const Input& u);

// Exact Jacobians df/dx (19x19) and df/du (19x4) of `dynamics`.
void dynamics_jacobians(const State& x, const Input& u, StateMatrix& df_dx,
                        StateInputMatrix& df_du);

// One classical RK4 step of `dt_s` with the input held, quaternion renormalised.
State rk4_step(const State& x, const Input& u, double dt_s);

// The same step and its exact Jacobians d x_next / dx and d x_next / du.
State rk4_step(const State& x, const Input& u, double dt_s, StateMatrix& dx_next_dx,
               StateInputMatrix& dx_next_du);

// --- 10-state UAV model, UGV motion as a parameter ---------------------------------------

// Continuous dynamics of the UAV states at an instant where the UGV moves as `ugv`.
UavState uav_dynamics(const UavState& x, const Input& u, const UgvMotion& ugv);

// Exact Jacobians of `uav_dynamics` with respect to the UAV state and the input.
void uav_dynamics_jacobians(const UavState& x, const Input& u, const UgvMotion& ugv,
                            UavStateMatrix& df_dx, UavInputMatrix& df_du);

// One RK4 step from an instant where the UGV moves as `ugv`; Omega advances by beta inside
// the step exactly as in the 19-state model, so the two agree to rounding.
UavState uav_rk4_step(const UavState& x, const Input& u, const UgvMotion& ugv, double dt_s);

// The same step and its exact Jacobians.
UavState uav_rk4_step(const UavState& x, const Input& u, const UgvMotion& ugv, double dt_s,
                      UavStateMatrix& dx_next_dx, UavInputMatrix& dx_next_du);

// Relative translational velocity (eq. 4): v + Omega x p. The UAV's velocity with the
// part induced by the frame's rotation removed.
Eigen::Vector3d translational_velocity(const UavState& x, const UgvMotion& ugv);

}  // namespace cover::model
