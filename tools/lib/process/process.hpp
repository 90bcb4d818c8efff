// Starting, signalling and reaping one child process: the one way this project runs programs (launch's
// Supervisor, the tests' ChildProcess, and bench/run's Python through process_c.h). stdin from /dev/null, stdout and stderr on one fd; optionally a process
// group of its own (a terminal's Ctrl-C then reaches only the parent, and a stop reaches the child's children)
// and SIGTERM when the thread that started it ends.
#pragma once

#include <sys/resource.h>
#include <sys/types.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace lcm_control::tools {

struct ProcessOptions {
  bool own_group = true;
  bool die_with_parent = true;  // PR_SET_PDEATHSIG: fires when the starting *thread* ends
  std::vector<int> cpus;        // pinned to these CPUs before exec (its threads inherit it); empty: any
};

// "K=V" for this process's environment with `overrides` added or replaced.
std::vector<std::string> environment_with(const std::map<std::string, std::string>& overrides);

// Starts argv[0] (a path) with env ("K=V"); its output goes to output_fd. If execve fails, the child writes why on
// output_fd and exits 127. Throws std::runtime_error when it cannot fork.
pid_t start_process(const std::vector<std::string>& argv, const std::vector<std::string>& env, int output_fd,
                    ProcessOptions options = {});

// sig, once, to the child's process group when it has one of its own, else to the child.
void signal_process(pid_t pid, int sig);

// Its exit code (128 + signal when a signal ended it) once it has exited; nullopt while it runs. block: wait.
// usage: what it used (CPU time, peak RSS), filled when it is reaped.
std::optional<int> reap_process(pid_t pid, bool block, rusage* usage = nullptr);

// The file execve should run for `name`: a path as given, else in first_dir (e.g. next to the running program),
// else the first executable match on PATH; "" when there is none.
std::string find_program(const std::string& name, const std::string& first_dir = "");

// Runs argv (argv[0] found by find_program) with stdout + stderr collected into *output; kills it after timeout_s.
// Returns the exit code, 128+signal if killed, or -1 if it could not start or timed out.
int run_and_wait(const std::vector<std::string>& argv, double timeout_s, std::string* output);

}  // namespace lcm_control::tools
