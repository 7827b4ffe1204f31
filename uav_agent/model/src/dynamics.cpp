#include "cover/model/dynamics.hpp"

#include "cover/model/quaternion.hpp"

namespace cover::model {
namespace {

using Eigen::Vector3d;

// Shared by both views: derivative of the UAV states (p, v, q) given the UGV quantities.
UavState uav_derivative(const UavState& x, const Input& u, const Vector3d& a, const Vector3d& omega,
                        const Vector3d& beta) {
  const Vector3d p = x.segment<3>(idx::kPosition);
  const Vector3d v = x.segment<3>(idx::kVelocity);
  const QuaternionWxyz q = x.segment<4>(idx::kQuaternion);
  const Eigen::Vector4d body_rates(0.0, u(input_idx::kRateX), u(input_idx::kRateY),
                                   u(input_idx::kRateZ));
  const Eigen::Vector4d frame_rates(0.0, omega.x(), omega.y(), omega.z());

  UavState dx;
  dx.segment<3>(idx::kPosition) = v;
  dx.segment<3>(idx::kVelocity) = -beta.cross(p) - 2.0 * omega.cross(v) -
                                  omega.cross(omega.cross(p)) +
                                  thrust_direction(q) * u(input_idx::kThrust) - a;
  dx.segment<4>(idx::kQuaternion) =
      0.5 * (right_product_matrix(body_rates) * q - left_product_matrix(frame_rates) * q);
  return dx;
}

// d q' / d q for q' = 1/2 (q (x) [0, w] - [0, Omega] (x) q): 1/2 (R([0, w]) - L([0, Omega])),
// written entry by entry (the same values as the two 4x4 product matrices, without building
// them: that cost more than the rest of the Jacobian).
Eigen::Matrix4d attitude_rate_jacobian(const Input& u, const Vector3d& omega) {
  const double a = u(input_idx::kRateX), b = u(input_idx::kRateY), c = u(input_idx::kRateZ);
  const double x = omega.x(), y = omega.y(), z = omega.z();
  const double h = 0.5;
  Eigen::Matrix4d m;
  m(0, 0) = 0.0, m(1, 0) = h * (a - x), m(2, 0) = h * (b - y), m(3, 0) = h * (c - z);
  m(0, 1) = h * (x - a), m(1, 1) = 0.0, m(2, 1) = -h * (c + z), m(3, 1) = h * (b + y);
  m(0, 2) = h * (y - b), m(1, 2) = h * (c + z), m(2, 2) = 0.0, m(3, 2) = -h * (a + x);
  m(0, 3) = h * (z - c), m(1, 3) = -h * (b + y), m(2, 3) = h * (a + x), m(3, 3) = 0.0;
  return m;
}

// Jacobians of `uav_derivative` w.r.t. the UAV states and the input.
void uav_derivative_jacobians(const UavState& x, const Input& u, const Vector3d& omega,
                              const Vector3d& beta, UavStateMatrix& df_dx, UavInputMatrix& df_du) {
  const QuaternionWxyz q = x.segment<4>(idx::kQuaternion);
  const Eigen::Matrix3d omega_skew = skew(omega);

  df_dx.setZero();
  df_dx.block<3, 3>(idx::kPosition, idx::kVelocity).setIdentity();
  df_dx.block<3, 3>(idx::kVelocity, idx::kPosition) = -skew(beta) - omega_skew * omega_skew;
  df_dx.block<3, 3>(idx::kVelocity, idx::kVelocity) = -2.0 * omega_skew;
  df_dx.block<3, 4>(idx::kVelocity, idx::kQuaternion) =
      thrust_direction_jacobian(q) * u(input_idx::kThrust);
  df_dx.block<4, 4>(idx::kQuaternion, idx::kQuaternion) = attitude_rate_jacobian(u, omega);

  df_du.setZero();
  df_du.block<3, 1>(idx::kVelocity, input_idx::kThrust) = thrust_direction(q);
  // q (x) [0, w] is linear in w: the last three columns of L(q).
  df_du.block<4, 3>(idx::kQuaternion, input_idx::kRateX) =
      0.5 * left_product_matrix(q).rightCols<3>();
}

// d(q / |q|) / dq.
Eigen::Matrix4d normalisation_jacobian(const Eigen::Vector4d& q) {
  const double norm = q.norm();
  const Eigen::Vector4d unit = q / norm;
  return (Eigen::Matrix4d::Identity() - unit * unit.transpose()) / norm;
}

// Classical RK4 with its forward sensitivities, for any state size. `Model` provides
//   Vector derivative(const Vector& x, const Input& u, double t);
//   void sensitivity(const Vector& x, const Input& u, double t, const Sens& dx_dz, Sens& dk_dz);
// the latter giving d f(x(z), u(z)) / dz = df/dx dx/dz + df/du du/dz for z = (x0, u).
// The sensitivity of each stage point w.r.t. z = (x, u) is propagated by the chain rule,
// which gives the exact Jacobian of the discrete map (not a linearisation of the ODE).
template <int NX, typename Model>
Eigen::Matrix<double, NX, 1> rk4_with_sensitivities(
    const Model& model, const Eigen::Matrix<double, NX, 1>& x, const Input& u, double h,
    Eigen::Matrix<double, NX, NX>* dx_next_dx, Eigen::Matrix<double, NX, kInputSize>* dx_next_du) {
  using Vector = Eigen::Matrix<double, NX, 1>;
  using Sens = Eigen::Matrix<double, NX, NX + kInputSize>;
  const bool want_jacobians = dx_next_dx != nullptr;

  const double offsets[4] = {0.0, 0.5 * h, 0.5 * h, h};
  const double weights[4] = {h / 6.0, h / 3.0, h / 3.0, h / 6.0};
  Vector stage_point = x;
  Vector next = x;
  // dx/dz of z = (x, u): [I 0], built once (clearing and setting it per call cost ~10 %
  // of the SAMPC prepare).
  static const Sens initial_sens = Sens::Identity();
  Sens stage_sens = initial_sens;
  Sens next_sens = initial_sens;
  for (int i = 0; i < 4; ++i) {
    const Vector k = model.derivative(stage_point, u, offsets[i]);
    next += weights[i] * k;
    Sens k_sens;
    if (want_jacobians) {
      // The first stage starts at x itself: dx/dz = [I 0], so dk/dz is the Jacobian.
      if (i == 0) {
        model.jacobian(stage_point, u, offsets[i], k_sens);
      } else {
        model.sensitivity(stage_point, u, offsets[i], stage_sens, k_sens);
      }
      next_sens += weights[i] * k_sens;
    }
    if (i < 3) {
      stage_point = x + offsets[i + 1] * k;
      if (want_jacobians) {
        // d(x + c k)/dz = [I 0] + c dk/dz, in one pass over the matrix.
        stage_sens.noalias() = initial_sens + offsets[i + 1] * k_sens;
      }
    }
  }

  // Renormalise the quaternion (it drifts off the unit sphere under RK4).
  const Eigen::Vector4d q = next.template segment<4>(idx::kQuaternion);
  if (want_jacobians) {
    const Eigen::Matrix4d dn = normalisation_jacobian(q);
    const Eigen::Matrix<double, 4, NX + kInputSize> rows =
        next_sens.template middleRows<4>(idx::kQuaternion);
    next_sens.template middleRows<4>(idx::kQuaternion).noalias() = dn.lazyProduct(rows);
    *dx_next_dx = next_sens.template leftCols<NX>();
    *dx_next_du = next_sens.template rightCols<kInputSize>();
  }
  next.template segment<4>(idx::kQuaternion) = q / q.norm();
  return next;
}

// The full model is autonomous: time offsets are ignored. Dense products: it serves the
// model API and tests, not the controller's loop.
struct FullModel {
  using Sens = Eigen::Matrix<double, kStateSize, kStateSize + kInputSize>;
  State derivative(const State& x, const Input& u, double) const { return dynamics(x, u); }
  void sensitivity(const State& x, const Input& u, double, const Sens& dx_dz, Sens& dk_dz) const {
    StateMatrix dfdx;
    StateInputMatrix dfdu;
    dynamics_jacobians(x, u, dfdx, dfdu);
    dk_dz.noalias() = dfdx * dx_dz;
    dk_dz.rightCols<kInputSize>() += dfdu;
  }
  void jacobian(const State& x, const Input& u, double t, Sens& dk_dz) const {
    sensitivity(x, u, t, Sens::Identity(), dk_dz);
  }
};

// The UAV model sees Omega(t) = Omega0 + beta t inside the step.
struct UavModel {
  const UgvMotion& ugv;
  UavState derivative(const UavState& x, const Input& u, double t) const {
    return uav_derivative(x, u, ugv.specific_force_m_s2,
                          ugv.angular_velocity_rad_s + t * ugv.angular_acceleration_rad_s2,
                          ugv.angular_acceleration_rad_s2);
  }

  // (lazyProduct: coefficient-based kernels; Eigen's default GEMM is slow at these sizes.)
  // df/dx dx_dz + [0 df/du] by blocks (the blocks of uav_derivative_jacobians): df/dx is
  // mostly zeros (p' = v; v' couples 3x3 and 3x4 blocks; q' depends on q only), which
  // halves the cost of the loop's most expensive product.
  using Sens = Eigen::Matrix<double, kUavStateSize, kUavStateSize + kInputSize>;

  // df/dx's non-zero blocks at (x, u, t).
  struct Blocks {
    Eigen::Matrix3d dv_dp;
    Eigen::Matrix3d dv_dv;
    Eigen::Matrix<double, 3, 4> dv_dq;
    Eigen::Matrix4d dq_dq;
  };
  Blocks blocks(const UavState& x, const Input& u, double t) const {
    const Vector3d omega = ugv.angular_velocity_rad_s + t * ugv.angular_acceleration_rad_s2;
    const Vector3d& beta = ugv.angular_acceleration_rad_s2;
    const QuaternionWxyz q = x.segment<4>(idx::kQuaternion);
    const Eigen::Matrix3d omega_skew = skew(omega);
    Blocks b;
    b.dv_dp = -skew(beta) - omega_skew * omega_skew;
    b.dv_dv = -2.0 * omega_skew;
    b.dv_dq = thrust_direction_jacobian(q) * u(input_idx::kThrust);
    b.dq_dq = attitude_rate_jacobian(u, omega);
    return b;
  }

  // df/du's columns: thrust moves v along the thrust direction, body rates move q.
  static void add_input_columns(const QuaternionWxyz& q, Sens& dk_dz) {
    dk_dz.middleRows<3>(idx::kVelocity).col(kUavStateSize + input_idx::kThrust) +=
        thrust_direction(q);
    dk_dz.middleRows<4>(idx::kQuaternion).rightCols<3>() +=
        0.5 * left_product_matrix(q).rightCols<3>();
  }

  // The attitude does not depend on p or v (q' involves q and the rates only), so the
  // attitude rows of every stage's sensitivity are zero in the p and v columns: the
  // products with them run over the last kAttitudeColumns columns only.
  static constexpr int kAttitudeColumns = kUavStateSize + kInputSize - idx::kQuaternion;

  void sensitivity(const UavState& x, const Input& u, double t, const Sens& dx_dz,
                   Sens& dk_dz) const {
    const Blocks b = blocks(x, u, t);
    const auto dq_dz = dx_dz.middleRows<4>(idx::kQuaternion).rightCols<kAttitudeColumns>();
    dk_dz.middleRows<3>(idx::kPosition) = dx_dz.middleRows<3>(idx::kVelocity);
    auto dv = dk_dz.middleRows<3>(idx::kVelocity);
    dv.noalias() = b.dv_dp.lazyProduct(dx_dz.middleRows<3>(idx::kPosition));
    dv.noalias() += b.dv_dv.lazyProduct(dx_dz.middleRows<3>(idx::kVelocity));
    dv.rightCols<kAttitudeColumns>().noalias() += b.dv_dq.lazyProduct(dq_dz);
    auto dq = dk_dz.middleRows<4>(idx::kQuaternion);
    dq.leftCols<idx::kQuaternion>().setZero();
    dq.rightCols<kAttitudeColumns>().noalias() = b.dq_dq.lazyProduct(dq_dz);
    add_input_columns(x.segment<4>(idx::kQuaternion), dk_dz);
  }

  // sensitivity() at dx_dz = [I 0]: the blocks written where they go, no products.
  void jacobian(const UavState& x, const Input& u, double t, Sens& dk_dz) const {
    const Blocks b = blocks(x, u, t);
    dk_dz.setZero();
    dk_dz.block<3, 3>(idx::kPosition, idx::kVelocity).setIdentity();
    dk_dz.block<3, 3>(idx::kVelocity, idx::kPosition) = b.dv_dp;
    dk_dz.block<3, 3>(idx::kVelocity, idx::kVelocity) = b.dv_dv;
    dk_dz.block<3, 4>(idx::kVelocity, idx::kQuaternion) = b.dv_dq;
    dk_dz.block<4, 4>(idx::kQuaternion, idx::kQuaternion) = b.dq_dq;
    add_input_columns(x.segment<4>(idx::kQuaternion), dk_dz);
  }
};

}  // namespace

State dynamics(const State& x, const Input& u) {
  const UgvMotion ugv = ugv_part(x);
  State dx = State::Zero();
  dx.head<kUavStateSize>() =
      uav_derivative(uav_part(x), u, ugv.specific_force_m_s2, ugv.angular_velocity_rad_s,
                     ugv.angular_acceleration_rad_s2);
  dx.segment<3>(idx::kAngularVelocity) = ugv.angular_acceleration_rad_s2;
  return dx;
}

void dynamics_jacobians(const State& x, const Input& u, StateMatrix& df_dx,
                        StateInputMatrix& df_du) {
  const Vector3d p = x.segment<3>(idx::kPosition);
  const Vector3d v = x.segment<3>(idx::kVelocity);
  const QuaternionWxyz q = x.segment<4>(idx::kQuaternion);
  const Vector3d omega = x.segment<3>(idx::kAngularVelocity);
  const Vector3d beta = x.segment<3>(idx::kAngularAccel);

  UavStateMatrix uav_dx;
  UavInputMatrix uav_du;
  uav_derivative_jacobians(uav_part(x), u, omega, beta, uav_dx, uav_du);
  df_dx.setZero();
  df_dx.topLeftCorner<kUavStateSize, kUavStateSize>() = uav_dx;
  df_du.setZero();
  df_du.topRows<kUavStateSize>() = uav_du;

  // v' w.r.t. the UGV quantities.
  df_dx.block<3, 3>(idx::kVelocity, idx::kSpecificForce) = -Eigen::Matrix3d::Identity();
  // -2 Omega x v - Omega x (Omega x p) = 2 v x Omega - (Omega (Omega.p) - p |Omega|^2).
  df_dx.block<3, 3>(idx::kVelocity, idx::kAngularVelocity) =
      2.0 * skew(v) - (omega * p.transpose() + omega.dot(p) * Eigen::Matrix3d::Identity() -
                       2.0 * p * omega.transpose());
  df_dx.block<3, 3>(idx::kVelocity, idx::kAngularAccel) = skew(p);  // -beta x p = p x beta
  // -1/2 [0, Omega] (x) q = -1/2 R(q) [0, Omega].
  df_dx.block<4, 3>(idx::kQuaternion, idx::kAngularVelocity) =
      -0.5 * right_product_matrix(q).rightCols<3>();
  df_dx.block<3, 3>(idx::kAngularVelocity, idx::kAngularAccel).setIdentity();
}

State rk4_step(const State& x, const Input& u, double dt_s) {
  return rk4_with_sensitivities<kStateSize>(FullModel{}, x, u, dt_s, nullptr, nullptr);
}

State rk4_step(const State& x, const Input& u, double dt_s, StateMatrix& dx_next_dx,
               StateInputMatrix& dx_next_du) {
  return rk4_with_sensitivities<kStateSize>(FullModel{}, x, u, dt_s, &dx_next_dx, &dx_next_du);
}

UavState uav_dynamics(const UavState& x, const Input& u, const UgvMotion& ugv) {
  return UavModel{ugv}.derivative(x, u, 0.0);
}

void uav_dynamics_jacobians(const UavState& x, const Input& u, const UgvMotion& ugv,
                            UavStateMatrix& df_dx, UavInputMatrix& df_du) {
  uav_derivative_jacobians(x, u, ugv.angular_velocity_rad_s, ugv.angular_acceleration_rad_s2, df_dx,
                           df_du);
}

UavState uav_rk4_step(const UavState& x, const Input& u, const UgvMotion& ugv, double dt_s) {
  return rk4_with_sensitivities<kUavStateSize>(UavModel{ugv}, x, u, dt_s, nullptr, nullptr);
}

UavState uav_rk4_step(const UavState& x, const Input& u, const UgvMotion& ugv, double dt_s,
                      UavStateMatrix& dx_next_dx, UavInputMatrix& dx_next_du) {
  return rk4_with_sensitivities<kUavStateSize>(UavModel{ugv}, x, u, dt_s, &dx_next_dx, &dx_next_du);
}

Eigen::Vector3d translational_velocity(const UavState& x, const UgvMotion& ugv) {
  return x.segment<3>(idx::kVelocity) +
         ugv.angular_velocity_rad_s.cross(x.segment<3>(idx::kPosition));
}

}  // namespace cover::model
