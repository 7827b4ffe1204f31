#include <gtest/gtest.h>

#include <random>

#include "cover/sampc/qp_riccati.hpp"

namespace cover::sampc {
namespace {

// A random stage-structured QP; `bound` sets how tight the input boxes are.
void fill_random_qp(RiccatiQp& qp, int horizon, double bound, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  const auto random = [&](auto m) {
    for (int i = 0; i < m.rows(); ++i)
      for (int j = 0; j < m.cols(); ++j) m(i, j) = normal(rng);
    return m;
  };
  for (int k = 0; k <= horizon; ++k) {
    QpNode& n = qp.nodes[k];
    n.A = MatrixXX::Identity() + 0.1 * random(MatrixXX());
    n.A.bottomLeftCorner<kAttitude, kTranslational>().setZero();  // QpNode's structure
    n.B = 0.3 * random(MatrixXU());
    n.c = 0.1 * random(VectorX());
    MatrixXX lq = random(MatrixXX());
    lq.topRows<3>().setZero();  // singular state weights, as in xy-z-ref
    n.Q = 0.2 * lq * lq.transpose();
    n.q = random(VectorX());
    n.S.setZero();
    n.S.rightCols<7>() = 0.05 * random(MatrixUX()).rightCols<7>();
    n.Q.bottomRightCorner<7, 7>().diagonal().array() += 0.1;  // keeps [Q S'; S R] convex
    n.R = MatrixUU::Identity() * 2.0;
    n.r = random(VectorU());
    n.lower = VectorU::Constant(-bound);
    n.upper = VectorU::Constant(bound);
  }
}

// Gradient of the total cost w.r.t. every du_k along the dynamics (adjoint recursion):
// an independent way to check optimality.
std::vector<VectorU> reduced_gradient(const RiccatiQp& qp, int horizon) {
  std::vector<VectorU> g(horizon);
  VectorX lambda = qp.nodes[horizon].Q * qp.dx(horizon) + qp.nodes[horizon].q;
  for (int k = horizon - 1; k >= 0; --k) {
    const QpNode& n = qp.nodes[k];
    g[k] = n.R * qp.du(k) + n.S * qp.dx(k) + n.r + n.B.transpose() * lambda;
    lambda = n.Q * qp.dx(k) + n.S.transpose() * qp.du(k) + n.q + n.A.transpose() * lambda;
  }
  return g;
}

void expect_kkt(const RiccatiQp& qp, int horizon, const VectorX& dx0) {
  EXPECT_LT((qp.dx(0) - dx0).norm(), 1e-12);
  for (int k = 0; k < horizon; ++k) {
    const QpNode& n = qp.nodes[k];
    EXPECT_LT((qp.dx(k + 1) - (n.A * qp.dx(k) + n.B * qp.du(k) + n.c)).norm(), 1e-9);
  }
  const auto g = reduced_gradient(qp, horizon);
  for (int k = 0; k < horizon; ++k) {
    for (int i = 0; i < kNu; ++i) {
      const double du = qp.du(k)(i), lo = qp.nodes[k].lower(i), hi = qp.nodes[k].upper(i);
      ASSERT_GE(du, lo - 1e-9);
      ASSERT_LE(du, hi + 1e-9);
      if (du <= lo + 1e-9) {
        EXPECT_GE(g[k](i), -1e-7) << "k=" << k << " i=" << i;
      } else if (du >= hi - 1e-9) {
        EXPECT_LE(g[k](i), 1e-7) << "k=" << k << " i=" << i;
      } else {
        EXPECT_NEAR(g[k](i), 0.0, 1e-7) << "k=" << k << " i=" << i;
      }
    }
  }
}

class RiccatiQpTest : public ::testing::TestWithParam<unsigned> {};

TEST_P(RiccatiQpTest, UnconstrainedSolutionSatisfiesKkt) {
  RiccatiQp qp;
  fill_random_qp(qp, 20, 1e6, GetParam());
  const VectorX dx0 = VectorX::Constant(0.3);
  const QpResult result = qp.solve(20, dx0, 10);
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 1);
  EXPECT_EQ(result.factorizations, 0);  // the prepared factorisation was the right one
  expect_kkt(qp, 20, dx0);
}

TEST_P(RiccatiQpTest, BoxConstrainedSolutionSatisfiesKkt) {
  RiccatiQp qp;
  fill_random_qp(qp, 20, 0.3, GetParam());
  const VectorX dx0 = VectorX::Constant(0.5);
  const QpResult result = qp.solve(20, dx0, 100);
  ASSERT_TRUE(result.converged);
  EXPECT_GT(result.factorizations, 0);  // the boxes were active: the active set moved
  expect_kkt(qp, 20, dx0);
}

TEST_P(RiccatiQpTest, IterationCapStillGivesAFeasibleImprovedPoint) {
  RiccatiQp qp;
  fill_random_qp(qp, 20, 0.3, GetParam());
  const VectorX dx0 = VectorX::Constant(0.5);
  qp.prepare(20);
  const QpResult capped = qp.solve_prepared(dx0, 1);
  const double capped_objective = qp.objective();
  for (int k = 0; k < 20; ++k) {
    EXPECT_TRUE((qp.du(k).array() >= qp.nodes[k].lower.array() - 1e-12).all());
    EXPECT_TRUE((qp.du(k).array() <= qp.nodes[k].upper.array() + 1e-12).all());
  }
  qp.solve_prepared(dx0, 100);
  EXPECT_LE(qp.objective(), capped_objective + 1e-12);
  EXPECT_EQ(capped.iterations, 1);
}

INSTANTIATE_TEST_SUITE_P(Seeds, RiccatiQpTest, ::testing::Values(1u, 2u, 3u, 4u, 5u, 6u));

}  // namespace
}  // namespace cover::sampc
