// bench_physics: what the simulated hardware costs on top of Bullet. For each
// model, in interleaved rounds, a block of the sim's full control step
// (Simulation::step: actuators -- transmissions, limits, PID, damping,
// friction -- around btMultiBodyDynamicsWorld::stepSimulation, plus handing it
// a command per actuator as SimIo does) against a block of bare stepSimulation
// of an identical multibody driven by an inline PD to the same set points (so
// Bullet integrates the same motion in both).
//   bench_physics [--rounds R] [--sub-blocks B] [--block-ms T] [--min-steps S] NAME URDF YAML [NAME URDF YAML ...]
// (a round: B blocks of about T ms of each variant, alternating; the fastest block of each counts)
// Prints one line per model and round, then a sanity line per model:
//   physics NAME NDOF ROUND BARE_US_PER_STEP FULL_US_PER_STEP
//   physics-check NAME ok|diverged MAX_ABS_JOINT_POSITION
// With --futex-loop STATE_BYTES COMMAND_BYTES (one model, run pinned to one CPU), the full variant is instead the
// bare step followed by a bare futex round trip to a forked echo (bench_pingpong futex-ping's), the bytes copied
// each way: the lockstep floor over shared memory measured as one loop, so that the caches and TLB the physics
// loses to the other process at each switch count too:
//   physics-futex NAME ROUND BARE_US_PER_STEP BARE_PLUS_ROUND_TRIP_US_PER_STEP
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "bench/pingpong.hpp"
#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "sim_server/simulation.hpp"

namespace {

using namespace lcm_control;
using lcm_control::bench::now_ns;

// One moving joint as the bare variant drives it: an inline PD on the same set point.
struct BareJoint {
  int link = -1;
  double kp = 0, kd = 0, center = 0, amplitude = 0;  // joint units
};

struct Case {
  std::string name;
  RobotModel model;
  std::unique_ptr<sim::Simulation> full;
  std::unique_ptr<sim::Multibody> bare;
  std::vector<double> center, amplitude;  // full: position commands center + amplitude * sin(2 pi t), actuator units
  std::vector<BareJoint> bare_joints;
  int64_t bare_steps = 0;
  int64_t steps_per_block = 1;
  bench::FutexPinger* futex_loop = nullptr;  // --futex-loop: the full variant is a bare step and a round trip
};

// Both variants start away from every limit (turret_bot's slider rests on its lower limit) and follow the same
// slow sine around there, so Bullet does the same work in both (same motion, broadphase updates, no limit rows).
// Full: Simulation::step with a position command per actuator (PID, saturation, transmission, damping, friction).
// Bare: the floor any controlled Bullet robot pays: stepSimulation plus one inline PD torque per joint.
void prepare(Case& c) {
  sim::SimulationRates rates;  // 1 kHz physics and control, as sim_server's default
  c.full = std::make_unique<sim::Simulation>(c.model, rates);
  c.bare = std::make_unique<sim::Multibody>(c.model, 1.0 / rates.physics_hz);
  c.bare->size_solver_buffers();
  sim::Actuators& act = c.full->actuators();
  for (int i = 0; i < act.size(); ++i) {
    const Joint* j = c.model.joint(act.joint(i));
    double mid = 0, amp = 0.5;
    if (j->has_position_limits) {
      if (j->lower > 0 || j->upper < 0) mid = 0.5 * (j->lower + j->upper);
      amp = std::min(amp, 0.2 * (j->upper - j->lower));
    }
    const int link = c.full->multibody().joints()[size_t(c.full->multibody().joint_index(j->name))].link;
    c.full->multibody().set_state(link, mid, 0);
    c.bare->set_state(link, mid, 0);
    const SimpleTransmission& map = c.model.transmission_for_joint(j->name)->map;  // commands are in actuator units
    c.center.push_back(map.joint_to_actuator_position(mid));
    c.amplitude.push_back(amp * map.reduction);
    BareJoint b;
    b.link = link;
    const auto g = c.model.pid_gains.find(j->name);
    if (g != c.model.pid_gains.end()) {
      b.kp = g->second.p;
      b.kd = g->second.d;
    }
    b.center = mid;
    b.amplitude = amp;
    c.bare_joints.push_back(b);
  }
  c.full->actuators().read(c.full->physics_dt());
}

void step_full(Case& c) {
  sim::Actuators& act = c.full->actuators();
  const double s = std::sin(2 * M_PI * c.full->time());
  for (int i = 0; i < act.size(); ++i)
    act.set_command(i, act.wire_mode(i), c.center[size_t(i)] + c.amplitude[size_t(i)] * s);
  c.full->step();
}

void step_bare(Case& c) {
  sim::Multibody& mb = *c.bare;
  const double s = std::sin(2 * M_PI * double(c.bare_steps) * mb.dt());
  for (const BareJoint& b : c.bare_joints)
    mb.add_torque(b.link, b.kp * (b.center + b.amplitude * s - mb.position(b.link)) - b.kd * mb.velocity(b.link));
  mb.step();
  ++c.bare_steps;
}

double run_block(Case& c, bool full, int64_t steps) {
  const int64_t t0 = now_ns();
  if (full && c.futex_loop) {
    for (int64_t k = 0; k < steps; ++k) {
      step_bare(c);
      c.futex_loop->round_trip_us();
    }
  } else if (full) {
    for (int64_t k = 0; k < steps; ++k) step_full(c);
  } else {
    for (int64_t k = 0; k < steps; ++k) step_bare(c);
  }
  return double(now_ns() - t0) / 1e3 / double(steps);
}

int usage() {
  std::fprintf(stderr,
               "usage: bench_physics [--rounds R] [--sub-blocks B] [--block-ms T] [--min-steps S] "
               "[--futex-loop STATE_BYTES COMMAND_BYTES] NAME URDF YAML ...\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  int rounds = 9, min_steps = 5, sub_blocks = 8;
  double block_ms = 0.5;
  int state_bytes = -1, command_bytes = -1;
  std::vector<Case> cases;
  std::unique_ptr<bench::FutexPinger> pinger;
  try {
    for (int k = 1; k < argc; ++k) {
      const std::string a = argv[k];
      if (a == "--rounds" && k + 1 < argc)
        rounds = std::atoi(argv[++k]);
      else if (a == "--block-ms" && k + 1 < argc)
        block_ms = std::atof(argv[++k]);
      else if (a == "--min-steps" && k + 1 < argc)
        min_steps = std::atoi(argv[++k]);
      else if (a == "--sub-blocks" && k + 1 < argc)
        sub_blocks = std::max(1, std::atoi(argv[++k]));
      else if (a == "--futex-loop" && k + 2 < argc) {
        state_bytes = std::atoi(argv[++k]);
        command_bytes = std::atoi(argv[++k]);
      }
      else if (a.rfind("--", 0) != 0 && k + 2 < argc) {
        Case c;
        c.name = a;
        c.model = load_robot_model(argv[k + 1], argv[k + 2]);
        cases.push_back(std::move(c));
        k += 2;
      } else
        return usage();
    }
    if (cases.empty() || rounds < 1 || (state_bytes >= 0 && (cases.size() != 1 || state_bytes < 1 || command_bytes < 1)))
      return usage();
    for (Case& c : cases) prepare(c);
    if (state_bytes > 0) {
      pinger = std::make_unique<bench::FutexPinger>(state_bytes, command_bytes);
      cases.front().futex_loop = pinger.get();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_physics: %s\n", e.what());
    return 1;
  }

  // Warm up (caches, branch predictors, Bullet's pools) and size the blocks to about block_ms.
  for (Case& c : cases) {
    run_block(c, false, 20 * min_steps);
    const double us = std::max(run_block(c, true, 20 * min_steps), 0.01);
    c.steps_per_block = std::max<int64_t>(min_steps, int64_t(block_ms * 1e3 / us));
  }
  for (int r = 0; r < rounds; ++r)
    for (size_t m = 0; m < cases.size(); ++m) {
      Case& c = cases[(m + size_t(r)) % cases.size()];
      // A round is `sub_blocks` short blocks of each variant, alternating (which goes first alternates too, so
      // neither always runs on a warmer cache); each variant's figure for the round is its fastest block: being
      // preempted (a shared machine) only ever adds time, so the minimum is the cost the code has.
      double bare = HUGE_VAL, full = HUGE_VAL;
      for (int j = 0; j < sub_blocks; ++j) {
        if ((r + j) % 2 == 0) {
          bare = std::min(bare, run_block(c, false, c.steps_per_block));
          full = std::min(full, run_block(c, true, c.steps_per_block));
        } else {
          full = std::min(full, run_block(c, true, c.steps_per_block));
          bare = std::min(bare, run_block(c, false, c.steps_per_block));
        }
      }
      if (c.futex_loop)
        std::printf("physics-futex %s %d %.4f %.4f\n", c.name.c_str(), r, bare, full);
      else
        std::printf("physics %s %zu %d %.4f %.4f\n", c.name.c_str(), c.full->multibody().joints().size(), r, bare,
                    full);
      std::fflush(stdout);
    }
  // Sanity: neither variant blew up (a timing of a diverged simulation means nothing).
  for (Case& c : cases) {
    double worst = 0;
    for (const sim::MultibodyJoint& j : c.full->multibody().joints())
      for (double q : {c.full->multibody().position(j.link), c.bare->position(j.link)})
        worst = std::isfinite(q) ? std::max(worst, std::abs(q)) : HUGE_VAL;
    std::printf("physics-check %s %s %.3g\n", c.name.c_str(), worst < 10 ? "ok" : "diverged", worst);
  }
  return 0;
}
