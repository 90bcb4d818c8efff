// How a loop process asks Linux for predictable CPU time: pinned to one CPU
// (--cpu; in lockstep both loop processes share one, see bench/README.md) and
// SCHED_FIFO with locked memory (--rt-priority), applied before any thread
// starts so LCM's receive thread gets the same.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace lcm_control {

struct SchedulingFlags {
  int cpu = -1;         // -1: any CPU
  int rt_priority = 0;  // 0: the normal scheduler; 1..99: SCHED_FIFO
};

void add_scheduling_flags(CLI::App& app, SchedulingFlags& f);

// Applies the flags to the calling process; call it before creating threads. Returns what was applied for the
// ready line ("" if nothing). Throws std::runtime_error naming the flag and what to do (a CPU this process may not
// use, SCHED_FIFO or mlockall not permitted).
std::string apply_scheduling(const SchedulingFlags& f);

// Lowers the calling process's priority to `nice` (0..19) for it and the threads it starts afterwards: for tools
// that watch the loop (the dashboard) and must not take its CPU. Throws std::runtime_error naming the value.
void lower_priority(int nice);

// Makes the calling thread a background worker named `name`: the normal scheduler (not the loop's SCHED_FIFO, which
// a thread inherits) at nice 19, so that on a shared CPU the loop thread runs first. Best effort: nothing is thrown.
void become_background_thread(const char* name);

// How late a timed sleep or poll of the calling thread (and of threads it starts afterwards) may wake, in
// nanoseconds (>= 1); Linux gives normal threads 50,000 ns, SCHED_FIFO ones none. Throws naming the value.
void set_timer_slack(long ns);

// Allocations over 256 KiB (a trajectory goal's bytes, its plan) mapped on their own and unmapped when freed, by
// whatever thread frees them. glibc raises that threshold after the first such free, and such chunks then come from
// the heap of the thread that made them: a worker freeing one there holds that heap's lock while the loop's thread
// waits for it (bench_goal_intake, GOAL_INTAKE_WHY: a SCHED_FIFO loop blocked in __lll_lock_wait_private for ~2 ms).
// For the loop processes, at start.
void map_large_allocations_apart();

// The CPU, among those this process may use, with the most idle time over `sample_ms`; -1 if it cannot tell.
int least_busy_cpu(int sample_ms = 100);

}  // namespace lcm_control
