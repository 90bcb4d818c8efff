// rt/log: what reaches a log from the bus or a file cannot act on the terminal or pose as a program's own line
// (issue 35, item 1), and a flood of lines is clipped and rate-limited.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "rt/log.hpp"

namespace lcm_control {
namespace {

// What the program's logger writes to stderr while f() runs.
template <class F>
std::string stderr_of(F&& f) {
  std::fflush(stderr);
  FILE* scratch = std::tmpfile();
  const int saved = dup(2);
  dup2(fileno(scratch), 2);
  f();
  spdlog::default_logger()->flush();
  std::fflush(stderr);
  dup2(saved, 2);
  close(saved);
  std::rewind(scratch);
  std::string out;
  for (int c; (c = std::fgetc(scratch)) != EOF;) out += char(c);
  std::fclose(scratch);
  return out;
}

class Logging : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { setup_logging("log_test"); }
};

TEST_F(Logging, ClipEscapesControlCharactersAndStatesTheLength) {
  EXPECT_EQ(clip("joint\x1b[2J\r\n\x07"), "joint\\x1b[2J\\r\\n\\x07");
  EXPECT_EQ(clip(std::string(100, 'a') + "\n", 10), "aaaaaaaaaa... (101 bytes)");
  EXPECT_EQ(escape_controls("a\nb", true), "a\n  b");
}

TEST_F(Logging, NoLoggedTextCanClearTheScreenColourOrForgeALine) {
  const std::string forged = "name\x1b[2J\x1b[31m\r\n[controller_manager] info: all good";
  const std::string out = stderr_of([&] { spdlog::warn("unknown controller '{}'", forged); });
  EXPECT_EQ(out.find('\x1b'), std::string::npos) << out;
  EXPECT_EQ(out.find('\r'), std::string::npos) << out;
  EXPECT_NE(out.find("name\\x1b[2J\\x1b[31m\\r\n  [controller_manager] info: all good"), std::string::npos) << out;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);)
    EXPECT_EQ(line.rfind("[controller_manager]", 0), std::string::npos) << "a forged line: " << line;
}

TEST_F(Logging, BusLogClipsAndLimitsAFlood) {
  BusLog log(20, 100);
  const std::string out = stderr_of([&] {
    // 1,000 lines: their 60 MB are built well within the one-second window even on a loaded machine (10,000 took
    // over a second there, and a second window let 20 more through).
    for (int k = 0; k < 1000; ++k)
      log.warn("goal " + std::to_string(k) + " from the bus: " + std::string(60000, 'x') + "\x1b[2J");
  });
  EXPECT_LT(out.size(), 20u * 200u) << "1,000 lines of 60 kB";
  EXPECT_EQ(log.suppressed(), 1000 - 20);
  EXPECT_EQ(out.find('\x1b'), std::string::npos);
}

// A client sending the same wrong message 200 times gets one line, then one with the count once the repeat interval
// has passed; a different line in between says how often the one before came.
TEST_F(Logging, BusLogWritesARepeatedLineOnceAndThenItsCount) {
  BusLog log(20, 400, 1000000);
  const std::string bad = "arm_controller: could not decode 24 bytes on 'arm_controller/command' as joint_trajectory_t";
  std::string out = stderr_of([&] {
    for (int k = 0; k < 196; ++k) log.warn(bad);
  });
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
  EXPECT_EQ(log.suppressed(), 195);
  out = stderr_of([&] {
    log.warn("arm_controller: another problem");
    log.warn(bad);
  });
  EXPECT_NE(out.find("another problem (the line before came 195 more times)"), std::string::npos) << out;
  out = stderr_of([&] {
    for (int k = 0; k < 50; ++k) log.warn(bad);
    usleep(1100000);
    log.warn(bad);
  });
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
  EXPECT_NE(out.find("as joint_trajectory_t (came 50 more times in the last "), std::string::npos) << out;
}

}  // namespace
}  // namespace lcm_control
