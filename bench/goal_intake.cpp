// bench_goal_intake: 100,000-point trajectory goals (3.6 MB each, four a second) sent over real LCM to the turret_bot's
// trajectory controller while a 1 kHz real-time hardware is played on absolute deadlines, in one process, as the
// controller manager program reads them: the shared bus's socket read directly, then poll() between cycles. Each
// period's busy time on the loop's thread (on_hardware_state + the socket + poll) is timed: with the goals taken in
// off the loop (the intake's thread, as the program does), in the loop (as before), and without goals. Also the
// cost of one goal's decode and plan on one thread.
//   bench_goal_intake [--seconds S] [--smoke]
// Prints per kind (none, off_loop, in_loop; none_fifo and off_loop_fifo with the loop's thread on SCHED_FIFO, as the
// program runs with --rt-priority, when permitted; none_fifo_own_cpu and off_loop_fifo_own_cpu with it on a CPU of
// its own, as the program runs with --cpu, the sender on the others)
//   goal_intake KIND PERIODS P50_US P99_US MAX_US OVER_1MS GOALS_SENT GOALS_TAKEN cpu CPU_P99_US CPU_MAX_US CPU_OVER_1MS
// where the first figures are wall time busy and the cpu ones the loop thread's own CPU time in those periods (the
// difference: time it waited for a CPU or a lock). With GOAL_INTAKE_WHY set, each period over 1 ms is explained on
// stderr: its CPU time, page faults and voluntary (blocked) and involuntary (preempted) context switches.
// and `goal_cost POINTS BYTES DECODE_MS PLAN_MS`.
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "bench/pingpong.hpp"
#include "bus/bus.hpp"
#include "controllers/trajectory.hpp"
#include "controller_manager/manager.hpp"
#include "controller_interface/registry.hpp"
#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"
#include "rt/clock.hpp"
#include "rt/scheduling.hpp"
#include "controllers/builtin.hpp"

namespace {

using namespace lcm_control;
using namespace lcm_control::cm;
using lcm_control::bench::resting_state;

constexpr int kPoints = 100000;

joint_trajectory_t goal_of(int points) {
  joint_trajectory_t g{};
  g.num_joints = 2;
  g.joint_names = {"j1", "j2"};
  g.num_points = points;
  g.points.resize(size_t(points));
  for (int i = 0; i < points; ++i) {
    auto& p = g.points[size_t(i)];
    p.time_from_start = 0.5 + i * 1e-4;
    p.num_positions = 2;
    p.positions = {0.5 + 0.2 * std::sin(i * 1e-3), 0.1 * std::cos(i * 1e-3)};
  }
  return g;
}

struct Figures {
  std::vector<double> busy_us, cpu_us;  // per period: wall time busy on the loop's thread, and its CPU time in it
  int sent = 0, taken = 0;
  bool fifo = false;                    // the loop's thread ran SCHED_FIFO (the program's --rt-priority)
};

double thread_cpu_us() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e6 + double(t.tv_nsec) * 1e-3;
}

// The calling thread on SCHED_FIFO at `priority` (0: back to the normal scheduler); false when not permitted.
bool set_fifo(int priority) {
  sched_param p{};
  p.sched_priority = priority;
  return pthread_setschedparam(pthread_self(), priority > 0 ? SCHED_FIFO : SCHED_OTHER, &p) == 0;
}

Figures run(const std::string& kind, double seconds, const std::string& dir, const std::string& url) {
  const std::string yaml = dir + "/bench_goal_intake.yaml";
  std::ofstream(yaml) << "joint_state_controller: {type: joint_state_controller/JointStateController, "
                         "publish_rate: 50}\n"
                         "trajectory_controller:\n  type: position_controllers/JointTrajectoryController\n"
                         "  joints: [j1, j2]\n";
  Figures f;
  // `_own_cpu`: the loop's thread (and the manager's threads, which inherit it) on the last CPU, the sender on the
  // others, as a robot computer keeps the loop's core to itself: the sender's work, and the kernel's on what it
  // sends, is then not on the loop's CPU.
  const bool own_cpu = kind.size() > 8 && kind.compare(kind.size() - 8, 8, "_own_cpu") == 0;
  const bool fifo = kind.find("_fifo") != std::string::npos;
  const int cpus = int(std::thread::hardware_concurrency());
  if (own_cpu && cpus < 2) return f;
  if (fifo && !set_fifo(50)) return f;  // not permitted here: no figures
  f.fifo = fifo;
  cpu_set_t loop_cpu, other_cpus, all_cpus;
  CPU_ZERO(&loop_cpu);
  CPU_ZERO(&other_cpus);
  pthread_getaffinity_np(pthread_self(), sizeof all_cpus, &all_cpus);
  CPU_SET(cpus - 1, &loop_cpu);
  for (int c = 0; c < cpus - 1; ++c) CPU_SET(c, &other_cpus);
  if (own_cpu) pthread_setaffinity_np(pthread_self(), sizeof loop_cpu, &loop_cpu);
  Registry registry;
  register_builtin(registry);
  Bus bus(url, "", "", HardwareReader::Direct);
  bus.set_pass_budget_us(250);  // as the controller manager program reads
  RobotModel model = load_robot_model(std::string(LCM_CONTROL_SOURCE_DIR) + "/config/turret_bot.urdf", {yaml});
  hardware_state_t st = resting_state(model, 7, false);
  ManagerOptions options;
  options.slice_us = 250;
  options.intake_thread = kind.rfind("off_loop", 0) == 0;
  ControllerManager cm(std::move(model), bus, registry, options);
  for (const char* n : {"joint_state_controller", "trajectory_controller"})
    if (!cm.load(n).ok) throw std::runtime_error(std::string("cannot load ") + n);
  cm.switch_controllers({"joint_state_controller", "trajectory_controller"}, {}, 2, [](const Reply&) {});

  std::atomic<bool> done{false}, sending{true};
  std::atomic<int> sent{0}, taken{0};
  std::thread sender;
  if (kind.rfind("none", 0) != 0) {
    sender = std::thread([&] {
      set_fifo(0);  // a peer process's sender: the normal scheduler
      pthread_setaffinity_np(pthread_self(), sizeof(cpu_set_t), own_cpu ? &other_cpus : &all_cpus);
      lcm::LCM lc(url);
      // Each goal taken is followed on <name>/feedback under its id, and each one replaced is answered on
      // <name>/result: ids heard on either (the sender's own 3.6 MB goals crowd its socket, so one channel may miss).
      struct Heard {
        std::atomic<int>* taken;
        std::set<int64_t> ids;
        void on(const lcm::ReceiveBuffer*, const std::string&, const trajectory_status_t* r) {
          if (r->goal_id > 0 && ids.insert(r->goal_id).second) ++*taken;
        }
      } heard{&taken, {}};
      lc.subscribe("trajectory_controller/feedback", &Heard::on, &heard);
      lc.subscribe("trajectory_controller/result", &Heard::on, &heard);
      joint_trajectory_t g = goal_of(kPoints);
      std::vector<uint8_t> bytes(size_t(g.getEncodedSize()));
      int64_t next = monotonic_us() + 200000;
      while (!done) {
        lc.handleTimeout(10);
        if (!sending || monotonic_us() < next) continue;
        next += 250000;
        g.goal_id = sent + 1;
        g.encode(bytes.data(), 0, int(bytes.size()));
        if (lc.publish("trajectory_controller/command", bytes.data(), unsigned(bytes.size())) == 0) ++sent;
      }
    });
  }
  const int64_t periods = int64_t(seconds * 1000);
  const bool explain = getenv("GOAL_INTAKE_WHY") != nullptr;  // why a period took over 1 ms, on stderr
  f.busy_us.reserve(size_t(periods));
  timespec next{};
  clock_gettime(CLOCK_MONOTONIC, &next);
  for (int64_t k = 0; k < periods; ++k) {
    next.tv_nsec += 1000000;
    if (next.tv_nsec >= 1000000000) {
      next.tv_nsec -= 1000000000;
      ++next.tv_sec;
    }
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
    st.step = k;
    st.utime = k * 1000;
    rusage r0{}, r1{};
    if (explain) getrusage(RUSAGE_THREAD, &r0);
    const double c0 = thread_cpu_us();  // outside the timed window: reading a thread's CPU clock takes its run queue's lock
    const auto t0 = std::chrono::steady_clock::now();
    cm.on_hardware_state(st);
    const auto ta = std::chrono::steady_clock::now();
    bus.handle_us(0, 1000);
    const auto tb = std::chrono::steady_clock::now();
    cm.poll(monotonic_us());
    const auto t1 = std::chrono::steady_clock::now();
    const double c1 = thread_cpu_us();
    if (explain && std::chrono::duration<double, std::micro>(t1 - t0).count() > 1000) {
      getrusage(RUSAGE_THREAD, &r1);
      auto us = [](auto d) { return std::chrono::duration<double, std::micro>(d).count(); };
      auto tv = [](const timeval& a, const timeval& b) { return double(b.tv_sec - a.tv_sec) * 1e6 + double(b.tv_usec - a.tv_usec); };
      std::fprintf(stderr,
                   "over 1 ms at %.6f s: state %.0f us, bus %.0f us, poll %.0f us; cpu %.0f us (user %.0f, system %.0f), "
                   "minor faults %ld, major %ld, voluntary switches %ld, involuntary %ld\n",
                   std::chrono::duration<double>(t0.time_since_epoch()).count(), us(ta - t0), us(tb - ta), us(t1 - tb), c1 - c0, tv(r0.ru_utime, r1.ru_utime),
                   tv(r0.ru_stime, r1.ru_stime), r1.ru_minflt - r0.ru_minflt, r1.ru_majflt - r0.ru_majflt,
                   r1.ru_nvcsw - r0.ru_nvcsw, r1.ru_nivcsw - r0.ru_nivcsw);
    }
    if (k >= 100) {
      f.busy_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
      f.cpu_us.push_back(c1 - c0);
    }
  }
  sending = false;
  // Unmeasured cycles until the last goal sent is taken and its feedback (published by the controller's update) is
  // back, for at most 1 s.
  for (int64_t k = periods; k < periods + 1000 && (cm.taking_in() || taken < sent); ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    st.step = k;
    st.utime = k * 1000;
    cm.on_hardware_state(st);
    bus.handle_us(0, 1000);
    cm.poll(monotonic_us());
  }
  done = true;
  if (sender.joinable()) sender.join();
  if (fifo) set_fifo(0);
  if (own_cpu) pthread_setaffinity_np(pthread_self(), sizeof all_cpus, &all_cpus);
  f.sent = sent;
  f.taken = taken;
  return f;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
}

void goal_cost() {
  const joint_trajectory_t g = goal_of(kPoints);
  std::vector<uint8_t> bytes(size_t(g.getEncodedSize()));
  g.encode(bytes.data(), 0, int(bytes.size()));
  const auto t0 = std::chrono::steady_clock::now();
  joint_trajectory_t d;
  d.decode(bytes.data(), 0, int(bytes.size()));
  const auto t1 = std::chrono::steady_clock::now();
  std::vector<Waypoint> w(d.points.size());
  for (size_t i = 0; i < w.size(); ++i) {
    w[i].time = d.points[i].time_from_start;
    w[i].pos = d.points[i].positions;
  }
  const Trajectory::Plan plan = Trajectory::Plan::make(2, w, true);
  const auto t2 = std::chrono::steady_clock::now();
  std::printf("goal_cost %zu %zu %.2f %.2f\n", plan.points(), bytes.size(),
              std::chrono::duration<double, std::milli>(t1 - t0).count(),
              std::chrono::duration<double, std::milli>(t2 - t1).count());
}

}  // namespace

int main(int argc, char** argv) {
  map_large_allocations_apart();  // as the controller manager program does
  double seconds = 5;
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--smoke")) seconds = 1.0;
    else if (!std::strcmp(argv[k], "--seconds") && k + 1 < argc) seconds = std::atof(argv[++k]);
  }
  const std::string dir = std::filesystem::temp_directory_path().string();
  // A receive buffer that holds a whole goal's fragments (capped by net.core.rmem_max).
  const std::string url =
      "udpm://239.255.76.67:" + std::to_string(20000 + getpid() % 20000) + "?ttl=0&recv_buf_size=16777216";
  try {
    goal_cost();
    std::vector<std::string> kinds{"none",          "off_loop",          "in_loop", "none_fifo",
                                   "off_loop_fifo", "none_fifo_own_cpu", "off_loop_fifo_own_cpu"};
    if (const char* only = getenv("GOAL_INTAKE_KIND")) kinds = {only};  // one kind, e.g. to repeat it
    for (const std::string& kind : kinds) {
      const Figures f = run(kind, seconds, dir, url);
      if (f.busy_us.empty()) {
        std::printf("goal_intake %s skipped: SCHED_FIFO not permitted here (run as root, or with rtprio), or one CPU\n",
                    kind.c_str());
        continue;
      }
      auto over = [](const std::vector<double>& v) {
        return long(std::count_if(v.begin(), v.end(), [](double us) { return us > 1000; }));
      };
      std::printf("goal_intake %s %zu %.1f %.1f %.1f %ld %d %d cpu %.1f %.1f %ld\n", kind.c_str(), f.busy_us.size(),
                  percentile(f.busy_us, 0.5), percentile(f.busy_us, 0.99),
                  *std::max_element(f.busy_us.begin(), f.busy_us.end()), over(f.busy_us), f.sent, f.taken,
                  percentile(f.cpu_us, 0.99), *std::max_element(f.cpu_us.begin(), f.cpu_us.end()), over(f.cpu_us));
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_goal_intake: %s\n", e.what());
    return 1;
  }
  return 0;
}
