// --cpu and --rt-priority as sim_server and controller_manager apply them: each
// case runs in a forked child so the test process keeps its own scheduling.
#include "rt/scheduling.hpp"

#include <gtest/gtest.h>
#include <sched.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>

namespace lcm_control {
namespace {

// Runs f in a child; its exit code (0 = every check held).
int in_child(const std::function<int()>& f) {
  const pid_t pid = fork();
  if (pid == 0) _exit(f());
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 100;
}

int last_allowed_cpu() {
  cpu_set_t set;
  CPU_ZERO(&set);
  sched_getaffinity(0, sizeof(set), &set);
  int last = -1;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) last = c;
  return last;
}

// VmLck of this process, kB.
long locked_kb() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmLck:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

TEST(Scheduling, CpuPinsTheProcessAndThreadsItStartsLater) {
  const int cpu = last_allowed_cpu();
  ASSERT_GE(cpu, 0);
  EXPECT_EQ(0, in_child([cpu] {
              SchedulingFlags f;
              f.cpu = cpu;
              if (apply_scheduling(f) != "cpu " + std::to_string(cpu)) return 1;
              int seen = -1;
              std::thread t([&] { seen = sched_getcpu(); });  // as LCM's receive thread would be
              t.join();
              cpu_set_t set;
              CPU_ZERO(&set);
              sched_getaffinity(0, sizeof(set), &set);
              return CPU_COUNT(&set) == 1 && CPU_ISSET(cpu, &set) && seen == cpu ? 0 : 2;
            }));
}

TEST(Scheduling, ACpuThisProcessMayNotUseIsRefusedWithTheAllowedOnes) {
  SchedulingFlags f;
  f.cpu = 1000;
  try {
    apply_scheduling(f);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--cpu 1000: this process may only run on CPUs "), std::string::npos)
        << e.what();
  }
}

// Whether SCHED_FIFO and mlockall are allowed depends on the machine (root, capabilities, limits); whichever
// way it goes, what apply_scheduling says must be what the kernel did.
TEST(Scheduling, RtPriorityGivesSchedFifoOrSaysWhatToDo) {
  EXPECT_EQ(0, in_child([] {
              SchedulingFlags f;
              f.rt_priority = 10;
              std::string said;
              try {
                said = apply_scheduling(f);
              } catch (const std::runtime_error& e) {
                const std::string w = e.what();
                return sched_getscheduler(0) != SCHED_FIFO &&
                               w.find("--rt-priority 10: SCHED_FIFO not permitted") == 0 &&
                               w.find("CAP_SYS_NICE") != std::string::npos
                           ? 0
                           : 4;
              }
              sched_param p{};
              sched_getparam(0, &p);
              if (sched_getscheduler(0) != SCHED_FIFO || p.sched_priority != 10) return 3;
              if (said == "SCHED_FIFO 10, memory locked") return locked_kb() > 0 ? 0 : 5;
              return said == "SCHED_FIFO 10, memory not locked (needs CAP_IPC_LOCK or `ulimit -l unlimited`)" &&
                             locked_kb() == 0
                         ? 0
                         : 6;
            }));
}

TEST(Scheduling, LeastBusyCpuIsOneThisProcessMayUse) {
  const int cpu = least_busy_cpu(20);
  ASSERT_GE(cpu, 0);
  cpu_set_t set;
  CPU_ZERO(&set);
  sched_getaffinity(0, sizeof(set), &set);
  EXPECT_TRUE(CPU_ISSET(cpu, &set));
}

}  // namespace
}  // namespace lcm_control
