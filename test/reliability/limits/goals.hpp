// turret_bot trajectory goals of any size for the limits tests: two joints, positions only (36 bytes a point), a
// point each millisecond from 1 s on, each point's positions from `at` (default: 0.1 for both, within the limits).
#pragma once

#include <array>
#include <functional>

#include "lcm_control/joint_trajectory_t.hpp"

namespace lcm_control::testing {

inline joint_trajectory_t goal_of(int64_t id, int points,
                                  const std::function<std::array<double, 2>(int)>& at = {}) {
  joint_trajectory_t g{};
  g.goal_id = id;
  g.num_joints = 2;
  g.joint_names = {"j1", "j2"};
  g.num_points = points;
  g.points.resize(size_t(points));
  for (int i = 0; i < points; ++i) {
    auto& p = g.points[size_t(i)];
    p.time_from_start = 1.0 + i * 1e-3;
    p.num_positions = 2;
    const std::array<double, 2> q = at ? at(i) : std::array<double, 2>{0.1, 0.1};
    p.positions = {q[0], q[1]};
  }
  return g;
}

}  // namespace lcm_control::testing
