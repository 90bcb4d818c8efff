#include "test/support/process.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "tools/lib/process/process.hpp"

namespace lcm_control::testing {

namespace {
double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

std::string bin(const std::string& name) { return std::string(LCM_CONTROL_BIN_DIR) + "/" + name; }
std::string source(const std::string& relative) { return std::string(LCM_CONTROL_SOURCE_DIR) + "/" + relative; }

namespace {
long status_kb(pid_t pid, const std::string& field) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(field, 0) == 0) return std::atol(line.c_str() + field.size());
  return -1;
}
}  // namespace

long rss_kb(pid_t pid) { return status_kb(pid, "VmRSS:"); }
long peak_rss_kb(pid_t pid) { return status_kb(pid, "VmHWM:"); }

std::string ros2_robots_dir() {
  const char* env = std::getenv("LCM_CONTROL_ROS2_ROBOTS");
  const std::filesystem::path dir = env ? env : source("../shared/ros2_robots");
  return std::filesystem::is_directory(dir / "gz_cart") ? std::filesystem::canonical(dir).string() : "";
}

std::string temp_dir(const std::string& tag) {
  std::string tmpl = (std::filesystem::temp_directory_path() / ("lcm_control_" + tag + "_XXXXXX")).string();
  if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed for " + tmpl);
  return tmpl;
}

ChildProcess::ChildProcess(std::vector<std::string> argv, std::map<std::string, std::string> env) {
  char tmpl[] = "/tmp/lcm_control_child_XXXXXX";
  const int fd = mkstemp(tmpl);
  if (fd < 0) throw std::runtime_error("mkstemp failed");
  log_path_ = tmpl;
  // In the test's process group (ctest's timeout kill takes it with the test) and not tied to the thread that
  // started it: a test may start a child from a thread that ends before the child should.
  try {
    pid_ = tools::start_process(argv, tools::environment_with(env), fd, {false, false, {}});
  } catch (...) {
    close(fd);
    throw;
  }
  close(fd);
}

ChildProcess::~ChildProcess() {
  stop(3.0);
  if (!std::getenv("LCM_CONTROL_KEEP_TEST_LOGS")) std::remove(log_path_.c_str());
}

bool ChildProcess::running() {
  if (exited_ || pid_ <= 0) return false;
  if (const std::optional<int> code = tools::reap_process(pid_, false)) {
    exited_ = true;
    status_ = *code;
    return false;
  }
  return true;
}

int ChildProcess::wait(double timeout_s) {
  const double end = now_s() + timeout_s;
  while (running()) {
    // The last reading, not the largest: a mark read between fork and exec is the parent's.
    if (const long hwm = testing::peak_rss_kb(pid_); hwm >= 0) peak_rss_kb_ = hwm;
    if (now_s() > end) return -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return status_;
}

int ChildProcess::stop(double grace_s, int sig) {
  if (!running()) return status_;
  tools::signal_process(pid_, sig);
  const int rc = wait(grace_s);
  if (rc != -1) return rc;
  tools::signal_process(pid_, SIGKILL);
  return wait(5.0);
}

std::string ChildProcess::output() const {
  std::ifstream in(log_path_);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool ChildProcess::wait_for_output(const std::string& text, double timeout_s) {
  const double end = now_s() + timeout_s;
  while (now_s() < end) {
    if (output().find(text) != std::string::npos) return true;
    if (!running()) return output().find(text) != std::string::npos;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

}  // namespace lcm_control::testing
