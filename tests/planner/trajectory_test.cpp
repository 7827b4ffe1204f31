#include "cover/planner/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace cover::planner {
namespace {

TEST(Trajectory, DefaultHoldsTheOriginAtRest) {
  const Trajectory trajectory;
  EXPECT_EQ(trajectory.duration_s(), 0.0);
  EXPECT_TRUE(trajectory.is_finite());
  EXPECT_TRUE(trajectory.position(3.0).isZero());
  EXPECT_TRUE(trajectory.velocity(-1.0).isZero());
}

TEST(Trajectory, HoldStaysAtThePointForAnyTime) {
  const Eigen::Vector3d point(1.0, -2.0, 3.0);
  const Trajectory trajectory = Trajectory::hold(point);
  for (double t : {-5.0, 0.0, 0.5, 100.0, std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_TRUE(trajectory.position(t).isApprox(point)) << t;
    EXPECT_TRUE(trajectory.acceleration(t).isZero()) << t;
  }
}

// p(s) = s^3 on x over [0, 2] then a second piece; checks derivatives, clamping and lookup.
TEST(Trajectory, EvaluatesDerivativesAndClampsTime) {
  TrajectoryPiece first;
  first.duration_s = 2.0;
  first.coefficients(3, 0) = 1.0;  // x = s^3
  TrajectoryPiece second;
  second.duration_s = 1.0;
  second.coefficients(0, 1) = 5.0;  // y = 5 + s
  second.coefficients(1, 1) = 1.0;
  const Trajectory trajectory({first, second});
  EXPECT_DOUBLE_EQ(trajectory.duration_s(), 3.0);
  EXPECT_DOUBLE_EQ(trajectory.position(1.5).x(), 3.375);
  EXPECT_DOUBLE_EQ(trajectory.velocity(1.5).x(), 3.0 * 2.25);
  EXPECT_DOUBLE_EQ(trajectory.acceleration(1.5).x(), 9.0);
  EXPECT_DOUBLE_EQ(trajectory.jerk(1.5).x(), 6.0);
  EXPECT_DOUBLE_EQ(trajectory.position(2.5).y(), 5.5);
  EXPECT_DOUBLE_EQ(trajectory.position(99.0).y(), 6.0);  // clamped to the end
  EXPECT_DOUBLE_EQ(trajectory.position(-1.0).x(), 0.0);  // clamped to the start
}

TEST(Trajectory, DetectsNonFinitePieces) {
  TrajectoryPiece piece;
  piece.duration_s = 1.0;
  piece.coefficients(2, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(Trajectory({piece}).is_finite());
}

}  // namespace
}  // namespace cover::planner
