// bench_async: an is_async controller whose update sleeps 20 ms, beside the turret_bot's controllers, against the
// same loop without it and with it in the loop (is_async: false), in one process. A 1 kHz real-time hardware is
// played on absolute deadlines (clock_nanosleep); each ControllerManager::on_hardware_state (read, update, write,
// publish) is timed. The async controller must leave the cycle as it is without it; in the loop it stalls it.
//   bench_async [--seconds S] [--smoke]
// Prints per kind (none, async, sync)
//   async KIND CYCLES P50_US P99_US MAX_US OVER_PERIOD SLEEPER_UPDATES SKIPPED
// (OVER_PERIOD: cycles that took longer than the 1 ms period; SKIPPED: due updates skipped while one ran).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench/pingpong.hpp"
#include "bus/bus.hpp"
#include "controller_manager/manager.hpp"
#include "controller_interface/registry.hpp"
#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "controllers/builtin.hpp"

namespace {

using namespace lcm_control;
using namespace lcm_control::cm;
using lcm_control::bench::resting_state;

int g_sleeper_updates = 0;

// Sleeps 20 ms per update, then commands its joint where it is.
class Sleeper : public Controller {
 public:
  void init(ControllerContext& ctx) override { joint_ = ctx.claim(ctx.params().string("joint"), Interface::Position); }
  void starting(const Time&) override {}
  void update(const Time&, double) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    joint_->command = joint_->position;
    ++g_sleeper_updates;
  }

 private:
  JointData* joint_ = nullptr;
};

struct Figures {
  std::vector<double> cycle_us;
  int updates = 0;
  int64_t skipped = 0;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
}

Figures run(const std::string& kind, double seconds, const std::string& dir) {
  const std::string yaml = dir + "/bench_async_" + kind + ".yaml";
  std::ofstream(yaml) << "controller_manager:\n  ros__parameters:\n    update_rate: 1000\n"
                         "    jsb: {type: joint_state_broadcaster/JointStateBroadcaster}\n"
                         "    j2: {type: position_controllers/JointGroupPositionController}\n"
                         "    sleeper: {type: bench/Sleeper}\n"
                         "j2:\n  ros__parameters: {joints: [j2]}\n"
                         "sleeper:\n  ros__parameters: {joint: j1, is_async: "
                      << (kind == "async" ? "true" : "false") << "}\n";
  Registry registry;
  register_builtin(registry);
  registry.add("bench/Sleeper", [](const std::string&) { return std::make_unique<Sleeper>(); });
  Bus bus("memq://", "");
  RobotModel model = load_robot_model(std::string(LCM_CONTROL_SOURCE_DIR) + "/config/turret_bot.urdf", {yaml});
  hardware_state_t st = resting_state(model, 7, false);
  ControllerManager cm(std::move(model), bus, registry);
  std::vector<std::string> start = {"jsb", "j2"};
  if (kind != "none") start.push_back("sleeper");
  for (const auto& n : start)
    if (!cm.load(n).ok) throw std::runtime_error("cannot load " + n);
  cm.switch_controllers(start, {}, 2, [](const Reply&) {});
  Figures f;
  const int64_t cycles = int64_t(seconds * 1000);
  f.cycle_us.reserve(size_t(cycles));
  g_sleeper_updates = 0;
  timespec next{};
  clock_gettime(CLOCK_MONOTONIC, &next);
  for (int64_t k = 0; k < cycles; ++k) {
    next.tv_nsec += 1000000;
    if (next.tv_nsec >= 1000000000) {
      next.tv_nsec -= 1000000000;
      ++next.tv_sec;
    }
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
    st.step = k;
    st.utime = k * 1000;
    const auto t0 = std::chrono::steady_clock::now();
    cm.on_hardware_state(st);
    const auto t1 = std::chrono::steady_clock::now();
    if (k >= 100) f.cycle_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    cm.deliver_held();
    while (bus.lcm().handleTimeout(0) > 0) {
    }
  }
  f.updates = g_sleeper_updates;
  for (const auto& s : cm.loop().slots())
    if (s->async) f.skipped = s->async->skipped();
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 5;
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--smoke")) seconds = 0.5;
    else if (!std::strcmp(argv[k], "--seconds") && k + 1 < argc) seconds = std::atof(argv[++k]);
  }
  const std::string dir = std::filesystem::temp_directory_path().string();
  try {
    for (const char* kind : {"none", "async", "sync"}) {
      const Figures f = run(kind, std::string(kind) == "sync" ? std::min(seconds, 1.0) : seconds, dir);
      const auto over = std::count_if(f.cycle_us.begin(), f.cycle_us.end(), [](double us) { return us > 1000; });
      std::printf("async %s %zu %.1f %.1f %.1f %ld %d %ld\n", kind, f.cycle_us.size(), percentile(f.cycle_us, 0.5),
                  percentile(f.cycle_us, 0.99), f.cycle_us.empty() ? 0.0 : *std::max_element(f.cycle_us.begin(), f.cycle_us.end()),
                  long(over), f.updates, long(f.skipped));
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_async: %s\n", e.what());
    return 1;
  }
  return 0;
}
