#include "cover/planner/benchmark_problems.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace cover::planner {

namespace {

Eigen::Vector3d random_unit_vector(std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Vector3d v(normal(rng), normal(rng), normal(rng));
  const double norm = v.norm();
  return norm > 1e-9 ? Eigen::Vector3d(v / norm) : Eigen::Vector3d::UnitX();
}

}  // namespace

std::vector<StageProblem> make_benchmark_problems(int count, std::uint32_t seed) {
  // std::uniform_real_distribution is implementation-defined; the set is fixed per
  // standard library, which is enough for a benchmark on one machine.
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<StageProblem> problems;
  problems.reserve(static_cast<std::size_t>(std::max(count, 0)));
  for (int k = 0; k < count; ++k) {
    StageProblem p;
    p.goal_position_m = Eigen::Vector3d(0.0, 0.0, unit(rng) < 0.5 ? 1.5 : 0.3);
    // Uniform in the 8 m ball (cube root), kept above the ground plane of the UGV.
    Eigen::Vector3d offset = random_unit_vector(rng) * 8.0 * std::cbrt(unit(rng));
    p.start_position_m = p.goal_position_m + offset;
    p.start_position_m.z() = std::max(p.start_position_m.z(), 0.2);
    const Eigen::Vector3d v0 = random_unit_vector(rng) * 2.0 * unit(rng);
    p.vmax_m_s = 1.0 + 0.5 * unit(rng);
    p.amax_m_s2 = 1.5 + 1.5 * unit(rng);
    p.transition_stage = (k % 3 == 2);
    if (p.transition_stage) {
      p.ugv_angular_velocity_rad_s = Eigen::Vector3d(0.0, 0.0, (2.0 * unit(rng) - 1.0) * 0.5);
      // Choose the measured v so that eq. 23 yields the drawn v0.
      p.start_velocity_m_s = v0 - p.ugv_angular_velocity_rad_s.cross(p.start_position_m);
    } else {
      p.start_velocity_m_s = v0;
    }
    problems.push_back(p);
  }
  return problems;
}

}  // namespace cover::planner
