// A child process for end-to-end tests: started with its output captured to a
// file, bounded waits, and always stopped by its pid (SIGINT, then SIGKILL),
// started and reaped as launch does it (tools/lib/process.hpp).
#pragma once

#include <sys/types.h>
#include <unistd.h>

#include <cstdio>

#include <map>
#include <string>
#include <vector>

namespace lcm_control::testing {

class ChildProcess {
 public:
  // argv[0] is a path; env entries are added to (or replace) the test's environment.
  ChildProcess(std::vector<std::string> argv, std::map<std::string, std::string> env = {});
  ~ChildProcess();  // stops the process if it still runs
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  bool running();
  // Waits up to timeout_s; returns the exit code, 128+signal if killed, or -1 on timeout.
  int wait(double timeout_s);
  // SIGINT (or sig), waits up to grace_s, then SIGKILL. Returns the exit status as wait().
  int stop(double grace_s = 5.0, int sig = 2);
  // Everything the process wrote to stdout and stderr so far.
  std::string output() const;
  // Waits until output() contains text; false on timeout or if the process exits first.
  bool wait_for_output(const std::string& text, double timeout_s);
  // Its resident memory's high-water mark since its exec (VmHWM, kB) as wait() last read it while it ran; -1 before.
  long peak_rss_kb() const { return peak_rss_kb_; }

 private:
  pid_t pid_ = -1;
  int status_ = -1;
  bool exited_ = false;
  long peak_rss_kb_ = -1;
  std::string log_path_;
};

// Bytes this process writes to stdout and stderr while f() runs (both sent to a scratch file meanwhile): how much a
// flood of bad input makes an in-process server log.
template <class F>
long output_bytes(F&& f) {
  std::fflush(stdout);
  std::fflush(stderr);
  FILE* scratch = std::tmpfile();
  const int out = dup(1), err = dup(2);
  dup2(fileno(scratch), 1);
  dup2(fileno(scratch), 2);
  f();
  std::fflush(stdout);
  std::fflush(stderr);
  dup2(out, 1);
  dup2(err, 2);
  close(out);
  close(err);
  const long n = lseek(fileno(scratch), 0, SEEK_END);
  std::fclose(scratch);
  return n;
}

// Path of a program built by this project (build/bin/NAME).
std::string bin(const std::string& name);
// Path of a file in the source tree (e.g. "config/turret_bot.urdf").
std::string source(const std::string& relative);
// The real ROS 2 robot packages (../shared/ros2_robots beside the checkout, or $LCM_CONTROL_ROS2_ROBOTS), canonical;
// "" when absent (the tests that need them skip).
std::string ros2_robots_dir();
// In a test: `dir` is ros2_robots_dir(), and the test is skipped, saying why, when there is none.
#define NEED_ROS2_ROBOTS(dir)                                      \
  const std::string dir = ::lcm_control::testing::ros2_robots_dir(); \
  if (dir.empty()) GTEST_SKIP() << "no ../shared/ros2_robots (set LCM_CONTROL_ROS2_ROBOTS to the folder)"
// Resident memory of a process (VmRSS), kB; -1 when it is gone.
long rss_kb(pid_t pid);
// Its high-water mark since its last exec (VmHWM), kB; -1 when it is gone.
long peak_rss_kb(pid_t pid);
// A fresh, empty folder for one test's files.
std::string temp_dir(const std::string& tag);

}  // namespace lcm_control::testing
