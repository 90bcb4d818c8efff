// Joint-space splines for the trajectory controllers. Per joint and segment a
// polynomial: cubic when waypoints give positions (velocities then estimated,
// monotone, 0 at the last point) or positions and velocities, quintic when
// accelerations are given too; or, without interpolation (ROS 2's
// interpolation_method: none), the next waypoint's position from each
// waypoint's time on (the start state until the first). Before its start a
// trajectory holds its first state, after its end the last position. sample()
// does not allocate.
#pragma once

#include <cstddef>
#include <vector>

namespace lcm_control::cm {

struct SplineState {
  double pos = 0, vel = 0, acc = 0;
};

struct Waypoint {
  double time = 0;                    // absolute, seconds on the controller clock
  std::vector<double> pos, vel, acc;  // vel and acc empty when not given
};

class Trajectory {
 public:
  // Starts at t0 in `start` (one state per joint) and passes every waypoint
  // (times strictly increasing, after t0; validated by the caller).
  static Trajectory build(double t0, const std::vector<SplineState>& start, const std::vector<Waypoint>& points,
                          bool interpolate = true);
  // Holding still at `pos` from t0; set_hold() reuses the storage of a hold trajectory.
  static Trajectory hold(double t0, const std::vector<double>& pos);
  void set_hold(double t0, const double* pos);
  // Comes to rest from `from` (one state per joint) in `duration` seconds, as ros_controllers'
  // stop_trajectory_duration does (the rest point of a segment to the opposite velocity in twice the
  // time); duration <= 0 holds from.pos. Reuses the storage of a hold trajectory: no allocation.
  void set_stop(double t0, double duration, const SplineState* from);

  void sample(double t, size_t joint, SplineState& out) const;
  size_t joints() const { return segments_.size(); }
  double start_time() const { return t0_; }
  double end_time() const { return t1_; }

 private:
  struct Segment {
    double t0 = 0, t1 = 0;
    double c[6] = {0, 0, 0, 0, 0, 0};  // in tau = t - t0
  };
  static Segment cubic(double t0, double t1, double p0, double v0, double p1, double v1);
  static Segment quintic(double t0, double t1, const SplineState& a, const SplineState& b);
  std::vector<std::vector<Segment>> segments_;
  double t0_ = 0, t1_ = 0;
  bool steps_ = false;  // no interpolation
};

}  // namespace lcm_control::cm
