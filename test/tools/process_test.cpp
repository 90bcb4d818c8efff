// tools/lib/process: how every child process here is started, signalled and
// reaped (launch's Supervisor, the tests' ChildProcess, run_and_wait).
#include "tools/lib/process/process.hpp"
#include "tools/lib/process/process_c.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>

using namespace lcm_control::tools;

TEST(Process, RunAndWaitGivesTheExitCodeAndOutputOrSaysWhyNot) {
  std::string out;
  EXPECT_EQ(run_and_wait({"sh", "-c", "echo to-out; echo to-err >&2; exit 3"}, 10, &out), 3);
  EXPECT_NE(out.find("to-out"), std::string::npos) << out;
  EXPECT_NE(out.find("to-err"), std::string::npos) << out;
  EXPECT_EQ(run_and_wait({"no-such-program-lcm-control"}, 10, &out), -1);
  EXPECT_EQ(out, "cannot start no-such-program-lcm-control: not found on PATH");
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(run_and_wait({"sleep", "30"}, 0.2, &out), -1);  // killed at its timeout
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

TEST(Process, TheEnvironmentIsOursWithTheOverrides) {
  char tmpl[] = "/tmp/lcm_control_process_test_XXXXXX";
  const int fd = mkstemp(tmpl);
  ASSERT_GE(fd, 0);
  const pid_t pid = start_process({"/bin/sh", "-c", "echo \"$LCM_CONTROL_PROCESS_TEST;$HOME\""},
                                  environment_with({{"LCM_CONTROL_PROCESS_TEST", "set"}}), fd, {false, false, {}});
  close(fd);
  EXPECT_EQ(reap_process(pid, true), 0);
  FILE* f = fopen(tmpl, "r");
  char line[512] = {};
  ASSERT_NE(fgets(line, sizeof line, f), nullptr);
  fclose(f);
  unlink(tmpl);
  const char* home = getenv("HOME");
  EXPECT_EQ(std::string(line), "set;" + std::string(home ? home : "") + "\n");
}

TEST(Process, AStopReachesTheChildsOwnGroupOnceAndAMissingProgramExits127) {
  // sh traps SIGINT and counts; its foreground sleep only ends early if the SIGINT reached the whole group.
  char tmpl[] = "/tmp/lcm_control_process_test_XXXXXX";
  const int fd = mkstemp(tmpl);
  ASSERT_GE(fd, 0);
  const pid_t pid = start_process({"/bin/sh", "-c", "n=0; trap 'n=$((n+1))' INT; sleep 30; echo got $n; exit 5"},
                                  environment_with({}), fd, {});
  close(fd);
  // Signalled once sh runs its sleep (its trap is set by then), however long a loaded machine takes to get there.
  const std::string children = "/proc/" + std::to_string(pid) + "/task/" + std::to_string(pid) + "/children";
  for (int k = 0; k < 500; ++k) {
    std::ifstream in(children);
    std::string child;
    if (in >> child) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(getpgid(pid), pid);
  signal_process(pid, SIGINT);
  std::optional<int> code;
  for (int k = 0; k < 500 && !code; ++k) {
    code = reap_process(pid, false);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!code) {
    signal_process(pid, SIGKILL);
    reap_process(pid, true);
  }
  ASSERT_TRUE(code.has_value()) << "the sleep in its group did not get the SIGINT";
  EXPECT_EQ(*code, 5);
  FILE* f = fopen(tmpl, "r");
  char line[128] = {};
  ASSERT_NE(fgets(line, sizeof line, f), nullptr);
  fclose(f);
  unlink(tmpl);
  EXPECT_EQ(std::string(line), "got 1\n");  // once, not twice

  const int devnull = open("/dev/null", O_WRONLY);
  const pid_t missing = start_process({"/no/such/program"}, environment_with({}), devnull, {false, false, {}});
  close(devnull);
  EXPECT_EQ(reap_process(missing, true), 127);
}

// bench/run's Python goes through the C interface: a child pinned to one CPU, and what it used once reaped.
TEST(Process, TheCInterfacePinsAChildAndReportsItsUsage) {
  char tmpl[] = "/tmp/lcm_control_process_test_XXXXXX";
  const int fd = mkstemp(tmpl);
  ASSERT_GE(fd, 0);
  const char* argv[] = {"/bin/sh", "-c", "grep Cpus_allowed_list /proc/self/status; i=0; while [ $i -lt 20000 ]; do i=$((i+1)); done",
                        nullptr};
  const int cpu[] = {0};
  const int pid = lcm_control_start_process(argv, fd, cpu, 1, 0);
  close(fd);
  ASSERT_GT(pid, 0);
  int code = -1;
  double user = -1, system = -1;
  long rss = -1;
  EXPECT_EQ(lcm_control_reap_process(pid, 1, &code, &user, &system, &rss), 1);
  EXPECT_EQ(code, 0);
  EXPECT_GT(user + system, 0.0);
  EXPECT_GT(rss, 100);  // kB: a shell is more than that
  EXPECT_EQ(lcm_control_reap_process(pid, 0, &code, nullptr, nullptr, nullptr), -1);  // reaped already
  FILE* f = fopen(tmpl, "r");
  char line[256] = {};
  ASSERT_NE(f, nullptr);
  ASSERT_NE(fgets(line, sizeof line, f), nullptr);
  fclose(f);
  unlink(tmpl);
  EXPECT_STREQ(line, "Cpus_allowed_list:\t0\n");

  const int none[] = {4095};  // no such CPU: said, exit 127
  const char* sh[] = {"/bin/true", nullptr};
  const int bad = lcm_control_start_process(sh, open("/dev/null", O_WRONLY | O_CLOEXEC), none, 1, 0);
  ASSERT_GT(bad, 0);
  EXPECT_EQ(lcm_control_reap_process(bad, 1, &code, nullptr, nullptr, nullptr), 1);
  EXPECT_EQ(code, 127);
}
