// Joint-space splines for the trajectory controllers. Per joint and segment a
// polynomial: cubic when waypoints give positions (velocities then estimated,
// monotone, 0 at the last point) or positions and velocities, quintic when
// accelerations are given too; or, without interpolation (ROS 2's
// interpolation_method: none), the next waypoint's position from each
// waypoint's time on (the start state until the first). Before its start a
// trajectory holds its first state, after its end the last position. sample()
// does not allocate.
// A goal's trajectory is planned before its start state is known (Plan, off the
// control loop: all but the two segments the start state reaches) and started
// in the loop (Trajectory::start, O(joints)).
#pragma once

#include <cstddef>
#include <vector>

namespace lcm_control::cm {

struct SplineState {
  double pos = 0, vel = 0, acc = 0;
};

struct Waypoint {
  double time = 0;                    // seconds: absolute for build(), from the start for Plan::make()
  std::vector<double> pos, vel, acc;  // vel and acc empty when not given
};

class Trajectory {
  struct Segment {
    double t0 = 0, t1 = 0;  // seconds from the trajectory's start
    double c[6] = {0, 0, 0, 0, 0, 0};  // in tau = t - t0
  };

 public:
  // A trajectory's waypoints worked out before its start: times from the start (strictly increasing, > 0;
  // validated by the caller), positions less an offset per joint that start() adds back (a continuous joint's turn,
  // a joint a partial goal leaves out).
  class Plan {
   public:
    static Plan make(size_t joints, const std::vector<Waypoint>& points, bool interpolate = true);
    size_t points() const { return points_; }
    double duration() const { return end_; }

   private:
    friend class Trajectory;
    struct Knot {
      double t = 0, p = 0, v = 0, a = 0;
      bool has_vel = false, has_acc = false;
    };
    struct Joint {
      std::vector<Segment> segments;  // one per waypoint; the first two are made by start()
      Knot first, second;             // the first two waypoints (second.v final)
    };
    std::vector<Joint> joints_;
    size_t points_ = 0;
    double end_ = 0;
    bool steps_ = false;
  };

  // `plan` from t0 in `start` (one state per joint, absolute positions); offset: per joint, added to the plan's
  // positions (empty: none). Takes the plan's storage: no allocation beyond the per-joint offsets.
  static Trajectory start(Plan&& plan, double t0, const std::vector<SplineState>& start,
                          const std::vector<double>& offset = {});
  // Starts at t0 in `start` (one state per joint) and passes every waypoint
  // (absolute times strictly increasing, after t0; validated by the caller).
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
  static Segment cubic(double t0, double t1, double p0, double v0, double p1, double v1);
  static Segment quintic(double t0, double t1, const SplineState& a, const SplineState& b);
  static Segment segment(const Plan::Knot& from, double from_v, const Plan::Knot& to, double to_v);
  void sample_relative(double t, const std::vector<Segment>& segs, SplineState& out) const;
  std::vector<std::vector<Segment>> segments_;
  std::vector<double> offset_;  // per joint, added to every position sampled
  double t0_ = 0, t1_ = 0;
  bool steps_ = false;  // no interpolation
};

}  // namespace lcm_control::cm
