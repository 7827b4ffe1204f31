#include <gtest/gtest.h>

#include <random>

#include "cover/model/dynamics.hpp"

namespace cover::model {
namespace {

// Central differences of a vector function of a fixed-size vector.
template <int NOut, int NIn, typename F>
Eigen::Matrix<double, NOut, NIn> numeric_jacobian(const F& f,
                                                  const Eigen::Matrix<double, NIn, 1>& at) {
  const double h = 1e-6;
  Eigen::Matrix<double, NOut, NIn> j;
  for (int i = 0; i < NIn; ++i) {
    Eigen::Matrix<double, NIn, 1> plus = at, minus = at;
    plus(i) += h;
    minus(i) -= h;
    j.col(i) = (f(plus) - f(minus)) / (2 * h);
  }
  return j;
}

class ModelJacobians : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override {
    std::mt19937 rng(1234 + GetParam());
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    for (int i = 0; i < kStateSize; ++i) x_(i) = 2.0 * uni(rng);
    x_.segment<4>(idx::kQuaternion) =
        Eigen::Vector4d(uni(rng), uni(rng), uni(rng), uni(rng)).normalized();
    x_(idx::kSpecificForce + 2) += kGravity_m_s2;
    u_ = Input(kGravity_m_s2 + 3.0 * uni(rng), 2.0 * uni(rng), 2.0 * uni(rng), uni(rng));
  }
  State x_;
  Input u_;
};

TEST_P(ModelJacobians, ContinuousFullModelMatchesFiniteDifferences) {
  StateMatrix a;
  StateInputMatrix b;
  dynamics_jacobians(x_, u_, a, b);
  const auto fx = [&](const State& x) { return dynamics(x, u_); };
  const auto fu = [&](const Input& u) { return dynamics(x_, u); };
  EXPECT_LT((a - numeric_jacobian<kStateSize, kStateSize>(fx, x_)).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LT((b - numeric_jacobian<kStateSize, kInputSize>(fu, u_)).cwiseAbs().maxCoeff(), 1e-7);
}

TEST_P(ModelJacobians, Rk4FullModelMatchesFiniteDifferences) {
  StateMatrix a;
  StateInputMatrix b;
  const State next = rk4_step(x_, u_, 0.1, a, b);
  EXPECT_LT((next - rk4_step(x_, u_, 0.1)).norm(), 1e-15);
  const auto fx = [&](const State& x) { return rk4_step(x, u_, 0.1); };
  const auto fu = [&](const Input& u) { return rk4_step(x_, u, 0.1); };
  EXPECT_LT((a - numeric_jacobian<kStateSize, kStateSize>(fx, x_)).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LT((b - numeric_jacobian<kStateSize, kInputSize>(fu, u_)).cwiseAbs().maxCoeff(), 1e-7);
}

TEST_P(ModelJacobians, Rk4UavModelMatchesFiniteDifferences) {
  const UavState uav = uav_part(x_);
  const UgvMotion ugv = ugv_part(x_);
  UavStateMatrix a;
  UavInputMatrix b;
  uav_rk4_step(uav, u_, ugv, 0.1, a, b);
  const auto fx = [&](const UavState& x) { return uav_rk4_step(x, u_, ugv, 0.1); };
  const auto fu = [&](const Input& u) { return uav_rk4_step(uav, u, ugv, 0.1); };
  EXPECT_LT((a - numeric_jacobian<kUavStateSize, kUavStateSize>(fx, uav)).cwiseAbs().maxCoeff(),
            1e-7);
  EXPECT_LT((b - numeric_jacobian<kUavStateSize, kInputSize>(fu, u_)).cwiseAbs().maxCoeff(), 1e-7);
  // The UAV-model Jacobian is the UAV block of the full one.
  StateMatrix full_a;
  StateInputMatrix full_b;
  rk4_step(x_, u_, 0.1, full_a, full_b);
  EXPECT_LT((a - full_a.topLeftCorner<kUavStateSize, kUavStateSize>()).norm(), 1e-12);
  EXPECT_LT((b - full_b.topRows<kUavStateSize>()).norm(), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(RandomStates, ModelJacobians, ::testing::Range(0, 8));

}  // namespace
}  // namespace cover::model
