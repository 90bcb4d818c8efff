#include "tools/lib/process/process.hpp"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace lcm_control::tools {

std::vector<std::string> environment_with(const std::map<std::string, std::string>& overrides) {
  std::map<std::string, std::string> all;
  for (char** e = environ; *e; ++e) {
    const char* eq = std::strchr(*e, '=');
    if (eq) all[std::string(static_cast<const char*>(*e), eq)] = eq + 1;
  }
  for (const auto& [k, v] : overrides) all[k] = v;
  std::vector<std::string> out;
  out.reserve(all.size());
  for (const auto& [k, v] : all) out.push_back(k + "=" + v);
  return out;
}

pid_t start_process(const std::vector<std::string>& argv, const std::vector<std::string>& env, int output_fd,
                    ProcessOptions options) {
  if (argv.empty()) throw std::invalid_argument("start_process: no program");
  // Everything the child needs is built before fork: between fork and exec a child of a threaded process may only
  // make async-signal-safe calls.
  std::vector<std::string> arg_copy = argv, env_copy = env;
  std::vector<char*> args, envp;
  for (auto& a : arg_copy) args.push_back(a.data());
  args.push_back(nullptr);
  for (auto& e : env_copy) envp.push_back(e.data());
  envp.push_back(nullptr);
  const std::string cannot = "cannot start " + argv[0] + ": execve failed (not found or not executable)\n";
  cpu_set_t cpus;
  CPU_ZERO(&cpus);
  for (int c : options.cpus)
    if (c >= 0 && c < CPU_SETSIZE) CPU_SET(c, &cpus);
  const std::string unpinned = "cannot start " + argv[0] + ": sched_setaffinity failed (no such CPU?)\n";
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    if (options.own_group) setpgid(0, 0);
    if (options.die_with_parent) {
      prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (getppid() != parent) _exit(127);
    }
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    signal(SIGPIPE, SIG_DFL);  // a parent that ignores it (Python does) must not hand that on
    const int devnull = open("/dev/null", O_RDONLY);
    dup2(devnull, 0);
    dup2(output_fd, 1);
    dup2(output_fd, 2);
    if (!options.cpus.empty() && sched_setaffinity(0, sizeof cpus, &cpus) != 0) {
      if (write(2, unpinned.data(), unpinned.size()) < 0) _exit(127);
      _exit(127);
    }
    execve(args[0], args.data(), envp.data());
    if (write(2, cannot.data(), cannot.size()) < 0) _exit(127);
    _exit(127);
  }
  return pid;
}

void signal_process(pid_t pid, int sig) {
  if (pid <= 0) return;
  if (getpgid(pid) == pid && kill(-pid, sig) == 0) return;  // once: a second SIGINT means "hurry" to launch
  kill(pid, sig);
}

std::optional<int> reap_process(pid_t pid, bool block, rusage* usage) {
  int st = 0;
  pid_t r;
  do {
    r = wait4(pid, &st, block ? 0 : WNOHANG, usage);
  } while (r < 0 && errno == EINTR);
  if (r != pid) return std::nullopt;
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

std::string find_program(const std::string& name, const std::string& first_dir) {
  namespace fs = std::filesystem;
  if (name.find('/') != std::string::npos) return name;
  std::error_code ec;
  if (!first_dir.empty() && fs::exists(fs::path(first_dir) / name, ec)) return (fs::path(first_dir) / name).string();
  const char* path = std::getenv("PATH");
  const std::string dirs = path ? path : "/usr/bin:/bin";
  for (size_t start = 0; start <= dirs.size();) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
    start = end + 1;
  }
  return "";
}

int run_and_wait(const std::vector<std::string>& argv, double timeout_s, std::string* output) {
  std::vector<std::string> args = argv;
  args[0] = find_program(argv[0]);
  if (args[0].empty()) {
    if (output) *output = "cannot start " + argv[0] + ": not found on PATH";
    return -1;
  }
  char tmpl[] = "/tmp/lcm_control_run_XXXXXX";
  const int fd = mkstemp(tmpl);
  if (fd < 0) return -1;
  int code = -1;
  try {
    const pid_t pid = start_process(args, environment_with({}), fd, {false, true, {}});
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    for (;;) {
      if (const std::optional<int> c = reap_process(pid, false)) {
        code = *c;
        break;
      }
      if (std::chrono::steady_clock::now() > end) {
        kill(pid, SIGKILL);
        reap_process(pid, true);
        break;
      }
      usleep(2000);
    }
  } catch (const std::exception& e) {
    if (output) *output = "cannot start " + argv[0] + ": " + e.what();
    close(fd);
    std::remove(tmpl);
    return -1;
  }
  close(fd);
  if (output) {
    std::ifstream in(tmpl);
    std::stringstream ss;
    ss << in.rdbuf();
    *output = ss.str();
  }
  std::remove(tmpl);
  return code;
}

}  // namespace lcm_control::tools
