#include "tools/supervisor.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "tools/support.hpp"

extern char** environ;

namespace lcm_control::tools {

namespace {
void say(const std::string& line) {
  fmt::print("[launch] {}\n", line);
  std::fflush(stdout);
}

// The file execve will run: next to launch, else the first match on PATH.
std::string resolve_program(const std::string& name, const std::string& exe_dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (name.find('/') != std::string::npos) return name;
  if (fs::exists(fs::path(exe_dir) / name, ec)) return (fs::path(exe_dir) / name).string();
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  size_t start = 0;
  while (start <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
    start = end + 1;
  }
  return name;  // execve fails and the child says so
}
}  // namespace

bool Child::clean() const {
  return code == 0 || (signalled && !killed && (code == 128 + SIGINT || code == 128 + SIGTERM));
}

Supervisor::Supervisor(std::vector<std::pair<std::string, std::string>> env) {
  exe_dir_ = std::filesystem::read_symlink("/proc/self/exe").parent_path().string();
  std::map<std::string, std::string> all;
  for (char** e = environ; *e; ++e) {
    const char* eq = std::strchr(*e, '=');
    if (eq) all[std::string(static_cast<const char*>(*e), eq)] = eq + 1;
  }
  for (auto& [k, v] : env) all[k] = v;
  for (auto& [k, v] : all) env_strings_.push_back(k + "=" + v);
}

Supervisor::~Supervisor() {
  for (auto& c : children_)
    if (!c->exited) {
      kill(-c->pid, SIGKILL);
      kill(c->pid, SIGKILL);
      reap(*c, true);
    }
}

Child& Supervisor::start(const std::string& name, std::vector<std::string> argv, bool required,
                         const std::string& ready_text) {
  auto c = std::make_unique<Child>();
  c->name = name;
  c->required = required;
  c->ready_text = ready_text;
  argv[0] = resolve_program(argv[0], exe_dir_);
  c->argv = argv;
  // Everything the child needs is built before fork: between fork and exec a
  // child of a threaded process may only make async-signal-safe calls.
  std::vector<char*> args, envp;
  for (auto& a : c->argv) args.push_back(a.data());
  args.push_back(nullptr);
  for (auto& e : env_strings_) envp.push_back(e.data());
  envp.push_back(nullptr);
  const std::string cannot = fmt::format("cannot start {}: execve failed (not found or not executable)\n", argv[0]);
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(127);
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    const int devnull = open("/dev/null", O_RDONLY);
    dup2(devnull, 0);
    dup2(fds[1], 1);
    dup2(fds[1], 2);
    execve(args[0], args.data(), envp.data());
    if (write(2, cannot.data(), cannot.size()) < 0) _exit(127);
    _exit(127);
  }
  close(fds[1]);
  fcntl(fds[0], F_SETFL, O_NONBLOCK);
  c->pid = pid;
  c->fd = fds[0];
  say(fmt::format("started {} (pid {}): {}", name, pid, fmt::join(c->argv, " ")));
  children_.push_back(std::move(c));
  return *children_.back();
}

void Supervisor::watch(std::vector<int> fds, std::function<void()> on_readable) {
  watch_fds_ = std::move(fds);
  on_watch_ = std::move(on_readable);
}

void Supervisor::pump(int timeout_ms) {
  std::vector<pollfd> pfds;
  std::vector<Child*> owners;
  for (auto& c : children_)
    if (c->fd >= 0) {
      pfds.push_back({c->fd, POLLIN, 0});
      owners.push_back(c.get());
    }
  for (const int fd : watch_fds_) pfds.push_back({fd, POLLIN, 0});
  poll(pfds.data(), pfds.size(), timeout_ms);
  for (size_t k = 0; k < owners.size(); ++k)
    if (pfds[k].revents) read_output(*owners[k]);
  bool watched = false;
  for (size_t k = owners.size(); k < pfds.size(); ++k) watched = watched || (pfds[k].revents & POLLIN);
  if (watched && on_watch_) on_watch_();
  for (auto& c : children_) reap(*c, false);
}

std::string Supervisor::reason_to_stop() const {
  for (const auto& c : children_)
    if (c->exited && !c->signalled && c->required) return exit_text(*c);
  return "";
}

void Supervisor::stop(const std::vector<Child*>& cs, int64_t deadline_us) {
  for (auto* c : cs)
    if (!c->exited) {
      c->signalled = true;
      if (kill(-c->pid, SIGINT) != 0) kill(c->pid, SIGINT);
    }
  auto all_exited = [&] {
    for (auto* c : cs)
      if (!c->exited) return false;
    return true;
  };
  wait_until([&] { return all_exited() || stop_requested(); }, double(deadline_us - monotonic_us()) / 1e6);
  for (auto* c : cs)
    if (!c->exited) {
      say(fmt::format("{} (pid {}) did not stop {}: killing it", c->name, c->pid,
                      stop_requested() ? "before the second Ctrl-C" : "in time"));
      c->killed = true;
      kill(-c->pid, SIGKILL);
      kill(c->pid, SIGKILL);
    }
  for (auto* c : cs) reap(*c, true);
}

std::string Supervisor::exit_text(const Child& c) {
  if (c.killed) return fmt::format("{} had to be killed", c.name);
  if (c.code > 128) return fmt::format("{} died of signal {} ({})", c.name, c.code - 128, strsignal(c.code - 128));
  return fmt::format("{} exited with code {}", c.name, c.code);
}

void Supervisor::read_output(Child& c) {
  char buf[4096];
  for (;;) {
    const ssize_t n = read(c.fd, buf, sizeof buf);
    if (n > 0) {
      c.partial.append(buf, size_t(n));
      size_t nl;
      while ((nl = c.partial.find('\n')) != std::string::npos) {
        print_line(c, c.partial.substr(0, nl));
        c.partial.erase(0, nl + 1);
      }
      continue;
    }
    if (n == 0 || (errno != EAGAIN && errno != EINTR)) {
      if (!c.partial.empty()) print_line(c, c.partial);
      c.partial.clear();
      close(c.fd);
      c.fd = -1;
    }
    return;
  }
}

// "[name] line", without repeating a "[name]" or "program: " the line already starts with.
void Supervisor::print_line(Child& c, std::string line) {
  if (line.find(c.ready_text) != std::string::npos || (c.ready_text == " ready" && line.rfind("ready", 0) == 0))
    c.ready = true;
  const std::string prefix = "[" + c.name + "]";
  const std::string program = std::filesystem::path(c.argv[0]).filename().string() + ": ";
  if (line.rfind(program, 0) == 0) line.erase(0, program.size());
  if (line.rfind(prefix, 0) == 0)
    fmt::print("{}\n", line);
  else
    fmt::print("{} {}\n", prefix, line);
  std::fflush(stdout);
}

void Supervisor::reap(Child& c, bool block) {
  if (c.exited) return;
  int st = 0;
  const pid_t r = waitpid(c.pid, &st, block ? 0 : WNOHANG);
  if (r != c.pid) return;
  if (c.fd >= 0) read_output(c);
  c.exited = true;
  c.code = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  if (!c.clean() || !c.signalled) say(exit_text(c));
}

}  // namespace lcm_control::tools
