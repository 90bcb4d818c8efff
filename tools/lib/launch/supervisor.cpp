#include "tools/lib/launch/supervisor.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "tools/lib/process/process.hpp"
#include "tools/lib/clients/wait.hpp"

namespace lcm_control::tools {

namespace {
void say(const std::string& line) {
  fmt::print("[launch] {}\n", line);
  std::fflush(stdout);
}
}  // namespace

bool Child::clean() const {
  return code == 0 || (signalled && !killed && (code == 128 + SIGINT || code == 128 + SIGTERM));
}

Supervisor::Supervisor(std::vector<std::pair<std::string, std::string>> env) {
  exe_dir_ = std::filesystem::read_symlink("/proc/self/exe").parent_path().string();
  std::map<std::string, std::string> overrides;
  for (auto& [k, v] : env) overrides[k] = v;  // the last of a name wins
  env_strings_ = environment_with(overrides);
}

Supervisor::~Supervisor() {
  for (auto& c : children_)
    if (!c->exited) {
      signal_process(c->pid, SIGKILL);
      reap(*c, true);
    }
}

Child& Supervisor::start(const std::string& name, std::vector<std::string> argv, bool required,
                         const std::string& ready_text) {
  auto c = std::make_unique<Child>();
  c->name = name;
  c->required = required;
  c->ready_text = ready_text;
  if (const std::string found = find_program(argv[0], exe_dir_); !found.empty())
    argv[0] = found;  // else execve fails and the child says so
  c->argv = argv;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  pid_t pid = -1;
  try {
    pid = start_process(c->argv, env_strings_, fds[1]);
  } catch (...) {
    close(fds[0]);
    close(fds[1]);
    throw;
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
      signal_process(c->pid, SIGINT);
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
      signal_process(c->pid, SIGKILL);
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
  if (!c.ready &&
      (line.find(c.ready_text) != std::string::npos || (c.ready_text == " ready" && line.rfind("ready", 0) == 0))) {
    c.ready = true;
    c.ready_line = line;
  }
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
  const std::optional<int> code = reap_process(c.pid, block);
  if (!code) return;
  if (c.fd >= 0) read_output(c);
  c.exited = true;
  c.code = *code;
  if (!c.clean() || !c.signalled) say(exit_text(c));
}

}  // namespace lcm_control::tools
