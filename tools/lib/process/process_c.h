/* tools/lib/process for programs that are not C++: bench/run's Python loads liblcm_control_process.so with ctypes,
   so the benchmarks start, signal and reap their children exactly as launch and the tests do. */
#ifndef LCM_CONTROL_PROCESS_C_H
#define LCM_CONTROL_PROCESS_C_H

#ifdef __cplusplus
extern "C" {
#endif

/* Starts argv[0] (a path; argv ends with NULL) with this environment, stdout and stderr on output_fd, stdin from
   /dev/null, SIGTERM when the calling thread ends, in a process group of its own if own_group, pinned to the n_cpus
   CPUs in cpus if n_cpus > 0. Returns its pid, or -1 when it cannot fork. */
int lcm_control_start_process(const char* const* argv, int output_fd, const int* cpus, int n_cpus, int own_group);

/* sig, once, to its process group when it has one of its own, else to it. */
void lcm_control_signal_process(int pid, int sig);

/* 1 once it has exited (reaped: *code is its exit code, 128 + signal when a signal ended it; *user_s, *system_s its
   CPU time; *maxrss_kb its peak resident set), 0 while it runs (block = 0), -1 if it is not our child. */
int lcm_control_reap_process(int pid, int block, int* code, double* user_s, double* system_s, long* maxrss_kb);

#ifdef __cplusplus
}
#endif

#endif
