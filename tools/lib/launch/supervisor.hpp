// Child processes for launch: each in its own process group (the terminal's
// Ctrl-C reaches launch only, which stops them in order), its output printed
// line by line prefixed with its name, stopped with SIGINT and then SIGKILL
// (started, signalled and reaped by tools/lib/process.hpp).
#pragma once

#include <sys/types.h>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bus/bus.hpp"

namespace lcm_control::tools {

struct Child {
  std::string name;
  std::vector<std::string> argv;
  bool required = true;    // its exit is a reason to stop everything
  pid_t pid = -1;
  int fd = -1;             // its stdout + stderr
  std::string partial;     // output after the last newline
  std::string ready_text = " ready";  // the line that says it is up
  bool ready = false;      // it printed a line containing ready_text
  std::string ready_line;  // that line
  bool exited = false;
  bool signalled = false;  // we asked it to stop
  bool killed = false;     // we had to SIGKILL it
  int code = 0;            // exit code, or 128 + signal
  bool clean() const;
};

class Supervisor {
 public:
  // env: variables set for every child on top of launch's environment.
  explicit Supervisor(std::vector<std::pair<std::string, std::string>> env);
  ~Supervisor();  // kills what still runs
  Supervisor(const Supervisor&) = delete;
  Supervisor& operator=(const Supervisor&) = delete;

  // argv[0]: a program next to launch, else on PATH, or a path. Throws if it cannot fork.
  Child& start(const std::string& name, std::vector<std::string> argv, bool required,
               const std::string& ready_text = " ready");

  // Also wait on fds (none: stop watching) and call on_readable when one has data.
  void watch(std::vector<int> fds, std::function<void()> on_readable);

  // Prints output and reaps exits for up to timeout_ms.
  void pump(int timeout_ms);

  // Pumps until pred() or timeout_s; false on timeout.
  template <class Pred>
  bool wait_until(Pred&& pred, double timeout_s);

  // Why to shut down: the first required child that exited by itself ("" if none).
  std::string reason_to_stop() const;

  // SIGINT to each child's group; waits until deadline_us (monotonic_us())
  // or a new stop request (a second Ctrl-C); then SIGKILL and reap.
  void stop(const std::vector<Child*>& children, int64_t deadline_us);

  std::vector<std::unique_ptr<Child>>& children() { return children_; }
  static std::string exit_text(const Child& c);

 private:
  void read_output(Child& c);
  void print_line(Child& c, std::string line);
  void reap(Child& c, bool block);

  std::vector<std::string> env_strings_;
  std::string exe_dir_;
  std::vector<std::unique_ptr<Child>> children_;
  std::vector<int> watch_fds_;
  std::function<void()> on_watch_;
};

template <class Pred>
bool Supervisor::wait_until(Pred&& pred, double timeout_s) {
  const int64_t end = monotonic_us() + int64_t(timeout_s * 1e6);
  while (!pred()) {
    if (monotonic_us() >= end) return false;
    pump(20);
  }
  return true;
}

}  // namespace lcm_control::tools
