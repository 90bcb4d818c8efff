#include "rt/scheduling.hpp"

#include <malloc.h>

#include <fmt/format.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

namespace lcm_control {

namespace {

std::vector<int> allowed_cpus() {
  std::vector<int> cpus;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) != 0) return cpus;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) cpus.push_back(c);
  return cpus;
}

std::string cpu_list(const std::vector<int>& cpus) {
  std::string s;
  for (int c : cpus) s += (s.empty() ? "" : ",") + std::to_string(c);
  return s;
}

// Idle jiffies (idle + iowait) per CPU from /proc/stat.
std::map<int, long long> idle_jiffies() {
  std::map<int, long long> idle;
  std::ifstream in("/proc/stat");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("cpu", 0) != 0 || line.size() < 4 || !std::isdigit(static_cast<unsigned char>(line[3]))) continue;
    std::istringstream f(line.substr(3));
    int cpu = -1;
    long long user = 0, nice = 0, system = 0, id = 0, iowait = 0;
    if (f >> cpu >> user >> nice >> system >> id >> iowait) idle[cpu] = id + iowait;
  }
  return idle;
}

// CAP_IPC_LOCK (bit 14 of CapEff) lets mlockall ignore RLIMIT_MEMLOCK.
bool may_lock_any_amount() {
  rlimit lim{};
  if (getrlimit(RLIMIT_MEMLOCK, &lim) == 0 && lim.rlim_cur == RLIM_INFINITY) return true;
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("CapEff:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> 14) & 1;
  return false;
}

}  // namespace

void add_scheduling_flags(CLI::App& app, SchedulingFlags& f) {
  app.add_option("--cpu", f.cpu,
                 "run on this CPU only (the process and LCM's receive thread); launch pins sim_server and "
                 "controller_manager to one CPU in lockstep")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--rt-priority", f.rt_priority,
                 "SCHED_FIFO priority 1-99 with memory locked (needs root, CAP_SYS_NICE or `ulimit -r`)")
      ->check(CLI::Range(1, 99));
}

std::string apply_scheduling(const SchedulingFlags& f) {
  std::vector<std::string> applied;
  if (f.cpu >= 0) {
    const std::vector<int> cpus = allowed_cpus();
    bool ok = false;
    for (int c : cpus) ok = ok || c == f.cpu;
    if (!ok)
      throw std::runtime_error(fmt::format("--cpu {}: this process may only run on CPUs {} (see `nproc`, `taskset -p "
                                           "$$`); pick one of those",
                                           f.cpu, cpu_list(cpus)));
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(f.cpu, &set);
    if (sched_setaffinity(0, sizeof(set), &set) != 0)
      throw std::runtime_error(fmt::format("--cpu {}: sched_setaffinity failed: {}", f.cpu, std::strerror(errno)));
    applied.push_back(fmt::format("cpu {}", f.cpu));
  }
  if (f.rt_priority > 0) {
    sched_param p{};
    p.sched_priority = f.rt_priority;
    if (sched_setscheduler(0, SCHED_FIFO, &p) != 0)
      throw std::runtime_error(fmt::format(
          "--rt-priority {}: SCHED_FIFO not permitted ({}); run as root, give the program CAP_SYS_NICE (`setcap "
          "cap_sys_nice+ep`), or allow it with `ulimit -r {}` (rtprio in /etc/security/limits.conf)",
          f.rt_priority, std::strerror(errno), f.rt_priority));
    applied.push_back(fmt::format("SCHED_FIFO {}", f.rt_priority));
    // Locking future pages is only safe when no memlock limit applies: under one, a later allocation would fail.
    if (may_lock_any_amount() && mlockall(MCL_CURRENT | MCL_FUTURE) == 0)
      applied.push_back("memory locked");
    else
      applied.push_back("memory not locked (needs CAP_IPC_LOCK or `ulimit -l unlimited`)");
  }
  std::string s;
  for (const auto& a : applied) s += (s.empty() ? "" : ", ") + a;
  return s;
}

void lower_priority(int nice) {
  if (nice < 0 || nice > 19) throw std::runtime_error(fmt::format("--nice {}: give 0 (unchanged) to 19", nice));
  // On Linux the nice value is per thread, and a thread starts with its creator's: call this before any thread.
  if (nice > 0 && setpriority(PRIO_PROCESS, 0, nice) != 0)
    throw std::runtime_error(fmt::format("--nice {}: setpriority failed ({})", nice, std::strerror(errno)));
}

void become_background_thread(const char* name) {
  sched_param p{};
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &p);
  (void)!setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), 19);  // Linux: a thread's own nice value
  pthread_setname_np(pthread_self(), name);
}

void map_large_allocations_apart() { mallopt(M_MMAP_THRESHOLD, 256 * 1024); }

void set_timer_slack(long ns) {
  if (ns < 1 || prctl(PR_SET_TIMERSLACK, static_cast<unsigned long>(ns), 0, 0, 0) != 0)
    throw std::runtime_error(fmt::format("--timer-slack-ns {}: give a number of nanoseconds >= 1{}", ns,
                                         ns < 1 ? "" : fmt::format(" (prctl failed: {})", std::strerror(errno))));
}

int least_busy_cpu(int sample_ms) {
  const std::vector<int> cpus = allowed_cpus();
  if (cpus.empty()) return -1;
  if (cpus.size() == 1) return cpus.front();
  const auto before = idle_jiffies();
  std::this_thread::sleep_for(std::chrono::milliseconds(sample_ms));
  const auto after = idle_jiffies();
  int best = -1;
  long long best_idle = -1;
  for (int c : cpus) {
    const auto b = before.find(c), a = after.find(c);
    if (b == before.end() || a == after.end()) continue;
    const long long idle = a->second - b->second;
    if (idle >= best_idle) {  // ties go to the higher CPU: CPU 0 usually takes more interrupts
      best_idle = idle;
      best = c;
    }
  }
  return best;
}

}  // namespace lcm_control
