#include "controller_manager/controllers/trajectory.hpp"

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

Trajectory Trajectory::build(double t0, const std::vector<SplineState>& start, const std::vector<Waypoint>& points,
                             bool interpolate) {
  Trajectory tr;
  tr.t0_ = t0;
  tr.t1_ = points.empty() ? t0 : points.back().time;
  tr.steps_ = !interpolate;
  const size_t n = start.size();
  tr.segments_.resize(n);
  for (size_t j = 0; j < n; ++j) {
    // Knots: the start state, then every waypoint.
    std::vector<double> t{t0}, p{start[j].pos}, v{start[j].vel}, a{start[j].acc};
    std::vector<bool> has_vel{true}, has_acc{true};
    for (const auto& w : points) {
      t.push_back(w.time);
      p.push_back(w.pos[j]);
      has_vel.push_back(!w.vel.empty());
      has_acc.push_back(!w.acc.empty());
      v.push_back(w.vel.empty() ? 0.0 : w.vel[j]);
      a.push_back(w.acc.empty() ? 0.0 : w.acc[j]);
    }
    for (size_t k = 1; k + 1 < t.size(); ++k) {
      if (has_vel[k]) continue;
      const double s0 = (p[k] - p[k - 1]) / (t[k] - t[k - 1]), s1 = (p[k + 1] - p[k]) / (t[k + 1] - t[k]);
      v[k] = s0 * s1 <= 0 ? 0.0 : 2.0 / (1.0 / s0 + 1.0 / s1);  // harmonic mean: no overshoot
    }
    for (size_t k = 1; k < t.size(); ++k) {
      if (has_acc[k])
        tr.segments_[j].push_back(quintic(t[k - 1], t[k], {p[k - 1], v[k - 1], a[k - 1]}, {p[k], v[k], a[k]}));
      else
        tr.segments_[j].push_back(cubic(t[k - 1], t[k], p[k - 1], v[k - 1], p[k], v[k]));
    }
  }
  return tr;
}

Trajectory Trajectory::hold(double t0, const std::vector<double>& pos) {
  Trajectory tr;
  tr.segments_.resize(pos.size(), std::vector<Segment>(1));
  tr.set_hold(t0, pos.data());
  return tr;
}

void Trajectory::set_hold(double t0, const double* pos) {
  t0_ = t1_ = t0;
  for (size_t j = 0; j < segments_.size(); ++j) {
    Segment& s = segments_[j][0];
    s = Segment{};
    s.t0 = s.t1 = t0;
    s.c[0] = pos[j];
  }
}

void Trajectory::set_stop(double t0, double duration, const SplineState* from) {
  t0_ = t0;
  t1_ = t0 + std::max(0.0, duration);
  for (size_t j = 0; j < segments_.size(); ++j) {
    Segment& s = segments_[j][0];
    const SplineState a{from[j].pos, duration > 0 ? from[j].vel : 0.0, 0.0};
    if (duration <= 0 || a.vel == 0) {
      s = Segment{};
      s.t0 = t0;
      s.t1 = t1_;
      s.c[0] = a.pos;
      continue;
    }
    const Segment there_and_back = quintic(t0, t0 + 2 * duration, a, {a.pos, -a.vel, 0.0});
    const double tau = duration;
    const double* c = there_and_back.c;
    const SplineState rest{c[0] + tau * (c[1] + tau * (c[2] + tau * (c[3] + tau * (c[4] + tau * c[5])))), 0.0, 0.0};
    s = quintic(t0, t1_, a, rest);
  }
}

void Trajectory::sample(double t, size_t joint, SplineState& out) const {
  const auto& segs = segments_[joint];
  if (segs.empty()) return;
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
