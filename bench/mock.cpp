// bench_mock: what mock hardware costs against Bullet, for the same robot in
// the same run. In interleaved rounds, a block of control steps of the
// Simulation with Backend::Mock and one with Backend::Bullet, each with a
// position command per actuator (a slow sine inside the limits) as SimIo hands
// them over; the fastest block of each counts.
//   bench_mock [--rounds R] [--steps N] URDF [YAML]
// Prints per round, then the summary:
//   mock ROUND BULLET_US_PER_STEP MOCK_US_PER_STEP
//   mock-summary BULLET_US MOCK_US RATIO BULLET_X_REAL_TIME MOCK_X_REAL_TIME   (1 kHz control, best blocks)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/pingpong.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "sim_server/simulation.hpp"

namespace {

using namespace lcm_control;
using lcm_control::bench::now_ns;

struct Variant {
  sim::Simulation sim;
  std::vector<double> center, amplitude;
  int64_t k = 0;
};

Variant make(const RobotModel& model, sim::Backend backend) {
  Variant v{sim::Simulation(model, {}, model.initial_positions, {}, backend), {}, {}, 0};
  const sim::PlayedHardware& hw = v.sim.hardware();
  for (int i = 0; i < hw.size(); ++i) {
    const Joint* j = model.joint(hw.joint(i));
    const bool limited = j && j->has_position_limits;
    v.center.push_back(limited ? 0.5 * (j->lower + j->upper) : 0.0);
    v.amplitude.push_back(limited ? 0.25 * (j->upper - j->lower) : 0.5);
  }
  return v;
}

// Microseconds per control step over `steps` steps.
double block(Variant& v, int steps) {
  sim::PlayedHardware& hw = v.sim.hardware();
  const int64_t t0 = now_ns();
  for (int s = 0; s < steps; ++s, ++v.k) {
    const double phase = std::sin(2 * M_PI * double(v.k) * 1e-3 * 0.2);
    for (int i = 0; i < hw.size(); ++i)
      hw.set_command(i, hardware_command_t::MODE_POSITION, v.center[size_t(i)] + v.amplitude[size_t(i)] * phase);
    v.sim.step();
  }
  return double(now_ns() - t0) / 1e3 / double(steps);
}

}  // namespace

int main(int argc, char** argv) {
  int rounds = 5, steps = 5000;
  std::vector<std::string> files;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--rounds" && k + 1 < argc)
      rounds = std::max(1, std::atoi(argv[++k]));
    else if (a == "--steps" && k + 1 < argc)
      steps = std::max(1, std::atoi(argv[++k]));
    else
      files.push_back(a);
  }
  if (files.empty() || files.size() > 2) {
    std::fprintf(stderr, "usage: bench_mock [--rounds R] [--steps N] URDF [YAML]\n");
    return 2;
  }
  try {
    const RobotModel model = load_robot_model(files[0], files.size() > 1 ? files[1] : "");
    Variant bullet = make(model, sim::Backend::Bullet), mock = make(model, sim::Backend::Mock);
    if (bullet.sim.hardware().size() == 0) {
      std::fprintf(stderr, "bench_mock: %s has no actuated joint to command\n", files[0].c_str());
      return 3;
    }
    double best_bullet = INFINITY, best_mock = INFINITY;
    for (int r = 0; r < rounds; ++r) {
      const double b = block(bullet, steps), m = block(mock, steps);
      best_bullet = std::min(best_bullet, b);
      best_mock = std::min(best_mock, m);
      std::printf("mock %d %.4f %.4f\n", r, b, m);
    }
    std::printf("mock-summary %.4f %.4f %.1f %.0f %.0f\n", best_bullet, best_mock, best_bullet / best_mock,
                1000.0 / best_bullet, 1000.0 / best_mock);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_mock: %s\n", e.what());
    return 3;
  }
  return 0;
}
