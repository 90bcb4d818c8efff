// Angle helpers: wrapping for continuous joints only (revolute joints use plain differences).
#pragma once

#include <cmath>

namespace lcm_control {

inline double normalize_angle(double a) {
  a = std::fmod(a + M_PI, 2.0 * M_PI);
  if (a < 0) a += 2.0 * M_PI;
  return a - M_PI;
}

// Shortest signed angle from `from` to `to`, in [-pi, pi).
inline double shortest_angular_distance(double from, double to) { return normalize_angle(to - from); }

}  // namespace lcm_control
