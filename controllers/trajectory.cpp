#include "controllers/trajectory.hpp"

#include <algorithm>

namespace lcm_control::cm {

Trajectory::Segment Trajectory::cubic(double t0, double t1, double p0, double v0, double p1, double v1) {
  Segment s;
  s.t0 = t0;
  s.t1 = t1;
  const double T = t1 - t0;
  s.c[0] = p0;
  s.c[1] = v0;
  s.c[2] = (3 * (p1 - p0) / T - 2 * v0 - v1) / T;
  s.c[3] = (2 * (p0 - p1) / T + v0 + v1) / (T * T);
  return s;
}

Trajectory::Segment Trajectory::quintic(double t0, double t1, const SplineState& a, const SplineState& b) {
  Segment s;
  s.t0 = t0;
  s.t1 = t1;
  const double T = t1 - t0, T2 = T * T, T3 = T2 * T;
  const double dp = b.pos - a.pos;
  s.c[0] = a.pos;
  s.c[1] = a.vel;
  s.c[2] = 0.5 * a.acc;
  s.c[3] = (20 * dp - (8 * b.vel + 12 * a.vel) * T - (3 * a.acc - b.acc) * T2) / (2 * T3);
  s.c[4] = (-30 * dp + (14 * b.vel + 16 * a.vel) * T + (3 * a.acc - 2 * b.acc) * T2) / (2 * T3 * T);
  s.c[5] = (12 * dp - 6 * (b.vel + a.vel) * T - (a.acc - b.acc) * T2) / (2 * T3 * T2);
  return s;
}

namespace {

// A waypoint's velocity when it gives none, from its neighbours: the harmonic mean of the two slopes, 0 where they
// differ in sign (no overshoot).
double estimated_velocity(double t0, double p0, double t1, double p1, double t2, double p2) {
  const double s0 = (p1 - p0) / (t1 - t0), s1 = (p2 - p1) / (t2 - t1);
  return s0 * s1 <= 0 ? 0.0 : 2.0 / (1.0 / s0 + 1.0 / s1);
}

}  // namespace

Trajectory::Segment Trajectory::segment(const Plan::Knot& from, double from_v, const Plan::Knot& to, double to_v) {
  if (to.has_acc) return quintic(from.t, to.t, {from.p, from_v, from.a}, {to.p, to_v, to.a});
  return cubic(from.t, to.t, from.p, from_v, to.p, to_v);
}

Trajectory::Plan Trajectory::Plan::make(size_t joints, const std::vector<Waypoint>& points, bool interpolate) {
  Plan plan;
  const size_t n = points.size();
  plan.points_ = n;
  plan.end_ = n == 0 ? 0.0 : points.back().time;
  plan.steps_ = !interpolate;
  plan.joints_.resize(joints);
  std::vector<Knot> k(n);
  for (size_t j = 0; j < joints; ++j) {
    for (size_t i = 0; i < n; ++i) {
      const Waypoint& w = points[i];
      k[i] = Knot{w.time, w.pos[j], w.vel.empty() ? 0.0 : w.vel[j], w.acc.empty() ? 0.0 : w.acc[j], !w.vel.empty(),
                  !w.acc.empty()};
    }
    for (size_t i = 1; i + 1 < n; ++i)  // the first waypoint's depends on the start: start() estimates it
      if (!k[i].has_vel) k[i].v = estimated_velocity(k[i - 1].t, k[i - 1].p, k[i].t, k[i].p, k[i + 1].t, k[i + 1].p);
    Joint& J = plan.joints_[j];
    J.segments.resize(n);
    for (size_t i = 2; i < n; ++i) J.segments[i] = segment(k[i - 1], k[i - 1].v, k[i], k[i].v);
    if (n > 0) J.first = k[0];
    if (n > 1) J.second = k[1];
  }
  return plan;
}

Trajectory Trajectory::start(Plan&& plan, double t0, const std::vector<SplineState>& start,
                             const std::vector<double>& offset) {
  Trajectory tr;
  tr.t0_ = t0;
  tr.t1_ = t0 + plan.end_;
  tr.steps_ = plan.steps_;
  const size_t joints = plan.joints_.size();
  tr.offset_.assign(joints, 0.0);
  if (!offset.empty()) tr.offset_ = offset;
  tr.segments_.resize(joints);
  for (size_t j = 0; j < joints; ++j) {
    Plan::Joint& J = plan.joints_[j];
    if (plan.points_ > 0) {
      const Plan::Knot s{0.0, start[j].pos - tr.offset_[j], start[j].vel, start[j].acc, true, true};
      const Plan::Knot& a = J.first;
      double v1 = a.v;
      if (!a.has_vel && plan.points_ > 1) v1 = estimated_velocity(s.t, s.p, a.t, a.p, J.second.t, J.second.p);
      J.segments[0] = segment(s, s.v, a, v1);
      if (plan.points_ > 1) J.segments[1] = segment(a, v1, J.second, J.second.v);
    }
    tr.segments_[j] = std::move(J.segments);
  }
  return tr;
}

Trajectory Trajectory::build(double t0, const std::vector<SplineState>& start, const std::vector<Waypoint>& points,
                             bool interpolate) {
  std::vector<Waypoint> relative = points;
  for (Waypoint& w : relative) w.time -= t0;
  return Trajectory::start(Plan::make(start.size(), relative, interpolate), t0, start);
}

Trajectory Trajectory::hold(double t0, const std::vector<double>& pos) {
  Trajectory tr;
  tr.segments_.resize(pos.size(), std::vector<Segment>(1));
  tr.offset_.assign(pos.size(), 0.0);
  tr.set_hold(t0, pos.data());
  return tr;
}

void Trajectory::set_hold(double t0, const double* pos) {
  t0_ = t1_ = t0;
  for (size_t j = 0; j < segments_.size(); ++j) {
    Segment& s = segments_[j][0];
    s = Segment{};
    s.c[0] = pos[j];
    offset_[j] = 0.0;
  }
}

void Trajectory::set_stop(double t0, double duration, const SplineState* from) {
  t0_ = t0;
  const double d = std::max(0.0, duration);
  t1_ = t0 + d;
  for (size_t j = 0; j < segments_.size(); ++j) {
    Segment& s = segments_[j][0];
    offset_[j] = 0.0;
    const SplineState a{from[j].pos, duration > 0 ? from[j].vel : 0.0, 0.0};
    if (duration <= 0 || a.vel == 0) {
      s = Segment{};
      s.t1 = d;
      s.c[0] = a.pos;
      continue;
    }
    const Segment there_and_back = quintic(0.0, 2 * duration, a, {a.pos, -a.vel, 0.0});
    const double tau = duration;
    const double* c = there_and_back.c;
    const SplineState rest{c[0] + tau * (c[1] + tau * (c[2] + tau * (c[3] + tau * (c[4] + tau * c[5])))), 0.0, 0.0};
    s = quintic(0.0, d, a, rest);
  }
}

void Trajectory::sample(double time, size_t joint, SplineState& out) const {
  const auto& segs = segments_[joint];
  if (segs.empty()) return;
  sample_relative(time - t0_, segs, out);
  out.pos += offset_[joint];
}

void Trajectory::sample_relative(double t, const std::vector<Segment>& segs, SplineState& out) const {
  const Segment* s = nullptr;
  double tau;
  if (t >= segs.back().t1) {
    s = &segs.back();
    tau = s->t1 - s->t0;
    const double* c = s->c;
    out.pos = c[0] + tau * (c[1] + tau * (c[2] + tau * (c[3] + tau * (c[4] + tau * c[5]))));
    out.vel = 0;
    out.acc = 0;
    return;
  }
  auto it = std::upper_bound(segs.begin(), segs.end(), t, [](double x, const Segment& sg) { return x < sg.t1; });
  s = &*it;
  tau = std::max(0.0, t - s->t0);
  const double* c = s->c;
  if (steps_) {  // the start state in the first segment, then the waypoint each segment ends at
    tau = it == segs.begin() ? 0.0 : s->t1 - s->t0;
    out.pos = c[0] + tau * (c[1] + tau * (c[2] + tau * (c[3] + tau * (c[4] + tau * c[5]))));
    out.vel = 0;
    out.acc = 0;
    return;
  }
  out.pos = c[0] + tau * (c[1] + tau * (c[2] + tau * (c[3] + tau * (c[4] + tau * c[5]))));
  out.vel = c[1] + tau * (2 * c[2] + tau * (3 * c[3] + tau * (4 * c[4] + tau * 5 * c[5])));
  out.acc = 2 * c[2] + tau * (6 * c[3] + tau * (12 * c[4] + tau * 20 * c[5]));
}

}  // namespace lcm_control::cm
