// A turret_bot session for end-to-end tests: controller_manager and the
// tutorial's three controllers come up first, then whatever the test wants to
// watch the bus with, then sim_server (lockstep or real time) for a bounded
// stretch of sim time. Every joint_states message is produced while sim_server runs, so a
// logger started before it and stopped after it sees all of them.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lcm_control::testing {

// Under lockstep the bus carries thousands of messages per second and every
// udpm socket on the port receives all of them, whatever it subscribes to. A
// receive buffer of 4 MB (net.core.rmem_max here) keeps a busy process (the
// JVM of DecodeLog's neighbours, a plotter running gnuplot) from dropping any.
inline std::string busy_bus_url() { return unique_lcm_url() + "&recv_buf_size=4194304"; }

class TurretBot {
 public:
  explicit TurretBot(std::string url) : url_(std::move(url)) {}

  const std::string& url() const { return url_; }
  std::map<std::string, std::string> env() const { return {{"LCM_DEFAULT_URL", url_}}; }

  // controller_manager, then the spawner until it reports the controllers running.
  void bring_up_controllers() {
    cm_ = std::make_unique<ChildProcess>(std::vector<std::string>{bin("controller_manager"), "--urdf", source("config/turret_bot.urdf"), "--config",
                                          source("config/turret_bot.yaml")},
                                         env());
    spawner_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{bin("spawner"), "joint_state_controller", "j1_controller", "j2_controller"}, env());
    ASSERT_TRUE(spawner_->wait_for_output("spawner: ready", 30)) << spawner_->output() << cm_->output();
  }

  // sim_server in `mode` for sim_seconds of sim time; returns when it has stopped.
  void run_sim(double sim_seconds, const std::string& mode = "lockstep", std::vector<std::string> extra = {}) {
    std::vector<std::string> argv{bin("sim_server"), "--urdf", source("config/turret_bot.urdf"), "--config",
                                  source("config/turret_bot.yaml"), "--mode", mode, "--duration",
                                  std::to_string(sim_seconds)};
    argv.insert(argv.end(), extra.begin(), extra.end());
    ChildProcess sim(argv, env());
    ASSERT_EQ(sim.wait(45), 0) << sim.output();
    sim_output_ = sim.output();
  }

  const std::string& sim_output() const { return sim_output_; }
  pid_t controller_manager_pid() const { return cm_ ? cm_->pid() : -1; }

  void shut_down() {
    if (spawner_) {
      EXPECT_EQ(spawner_->stop(10), 0) << spawner_->output();
    }
    if (cm_) {
      EXPECT_EQ(cm_->stop(10), 0) << cm_->output();
    }
  }

 private:
  std::string url_;
  std::unique_ptr<ChildProcess> cm_, spawner_;
  std::string sim_output_;
};

// lcm-logger recording url into path: every channel, or those channel_regex matches.
// lcm-logger 1.3.1 subscribes with liblcm's default queue of 30 messages per
// subscription and does not raise it; with ".*" under lockstep (10,000+
// messages/s) a few ms without the CPU overflows that queue and liblcm drops
// messages silently (seen: 5 of 361 joint_states missing from the log while
// state-logger, queue 1000, had them all). A channel regex queues fewer of
// them, but joint_states and a 60 Hz command under lockstep still come at
// 2,000 a second (15 ms of queue: 2 of 361 lost once on a loaded CI run); in
// real time they come at 120 a second.
inline std::unique_ptr<ChildProcess> start_lcm_logger(const std::string& url, const std::string& path,
                                                      const std::string& channel_regex = ".*") {
  auto p = std::make_unique<ChildProcess>(
      std::vector<std::string>{"/usr/bin/lcm-logger", "--lcm-url=" + url, "-c", channel_regex, "-f", path});
  EXPECT_TRUE(p->wait_for_output("Opening log file", 15)) << p->output();
  return p;
}

inline std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace lcm_control::testing
