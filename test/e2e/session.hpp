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

// A robot's processes for an end-to-end test, on a bus of its own: controller_manager, sim_server and the spawner,
// each started when the test says (the order is the test's), and stopped when the session goes.
class RobotSession {
 public:
  RobotSession(std::string urdf, std::string config, std::string url = unique_lcm_url())
      : urdf_(std::move(urdf)), config_(std::move(config)), url_(std::move(url)) {}
  virtual ~RobotSession() {
    for (auto* p : {&spawner_, &cm_, &sim_})
      if (*p) (*p)->stop(10);
  }
  RobotSession(const RobotSession&) = delete;
  RobotSession& operator=(const RobotSession&) = delete;

  const std::string& url() const { return url_; }
  const std::string& urdf() const { return urdf_; }
  const std::string& config() const { return config_; }
  std::map<std::string, std::string> env() const { return {{"LCM_DEFAULT_URL", url_}}; }

  void start_controller_manager(const std::vector<std::string>& extra = {}) {
    cm_ = std::make_unique<ChildProcess>(with({bin("controller_manager"), "--urdf", urdf_, "--config", config_}, extra),
                                         env());
  }
  // sim_server in the background; with ready_s > 0, until its "ready" line (at most ready_s).
  void start_sim(const std::vector<std::string>& extra = {}, double ready_s = 0) {
    sim_ = std::make_unique<ChildProcess>(with({bin("sim_server"), "--urdf", urdf_, "--config", config_}, extra),
                                          env());
    if (ready_s > 0) {
      ASSERT_TRUE(sim_->wait_for_output("ready (", ready_s)) << sim_->output();
    }
  }
  // The spawner with these controllers, until it reports them running.
  void spawn(const std::vector<std::string>& controllers) {
    spawner_ = std::make_unique<ChildProcess>(with({bin("spawner")}, controllers), env());
    ASSERT_TRUE(spawner_->wait_for_output("spawner: ready", 30))
        << spawner_->output() << (cm_ ? cm_->output() : "") << (sim_ ? sim_->output() : "");
  }

  // A program of the build run to its end (at most timeout_s): its exit code, its output in `out`.
  int run(std::vector<std::string> argv, std::string* out = nullptr, double timeout_s = 60) const {
    argv[0] = bin(argv[0]);
    ChildProcess p(argv, env());
    const int rc = p.wait(timeout_s);
    if (out) *out = p.output();
    return rc;
  }
  std::unique_ptr<ChildProcess> background(std::vector<std::string> argv) const {
    argv[0] = bin(argv[0]);
    return std::make_unique<ChildProcess>(argv, env());
  }

  // Stops one of them (SIGINT, then SIGKILL after 10 s): its exit code (-1 when it was not started); its output stays.
  int stop_spawner() { return spawner_ ? spawner_->stop(10) : -1; }
  int stop_sim() { return sim_ ? sim_->stop(10) : -1; }
  int stop_controller_manager() { return cm_ ? cm_->stop(10) : -1; }

  std::string sim_output() const { return sim_ ? sim_->output() : ""; }
  std::string cm_output() const { return cm_ ? cm_->output() : ""; }
  std::string spawner_output() const { return spawner_ ? spawner_->output() : ""; }
  pid_t controller_manager_pid() const { return cm_ ? cm_->pid() : -1; }

 protected:
  static std::vector<std::string> with(std::vector<std::string> argv, const std::vector<std::string>& extra) {
    argv.insert(argv.end(), extra.begin(), extra.end());
    return argv;
  }
  std::string urdf_, config_, url_;
  std::unique_ptr<ChildProcess> cm_, sim_, spawner_;
};

// A robot from its own files in lockstep: controller_manager and the spawner first, then sim_server, all with the
// same flags (package path, xacro arguments, namespace).
class LockstepSession : public RobotSession {
 public:
  LockstepSession(std::string urdf, std::string config, std::vector<std::string> flags)
      : RobotSession(std::move(urdf), std::move(config)), flags_(std::move(flags)) {}

  void start(const std::vector<std::string>& controllers, const std::vector<std::string>& sim_flags = {}) {
    start_controller_manager(flags_);
    ASSERT_NO_FATAL_FAILURE(spawn(controllers));
    start_sim(with(with({"--mode", "lockstep"}, flags_), sim_flags), 30);
  }
  const std::vector<std::string>& flags() const { return flags_; }

  // send-trajectory's exit code; its output in `output`.
  int send(const std::vector<std::string>& args, std::string& output) {
    return run(with({"send-trajectory"}, args), &output);
  }

 private:
  std::vector<std::string> flags_;
};

// turret_bot with the tutorial's three controllers, sim_server last and in the foreground for a bounded stretch.
class TurretBot : public RobotSession {
 public:
  explicit TurretBot(std::string url = unique_lcm_url())
      : RobotSession(source("config/turret_bot.urdf"), source("config/turret_bot.yaml"), std::move(url)) {}

  // controller_manager, then the spawner until it reports the controllers running.
  void bring_up_controllers() {
    start_controller_manager();
    spawn({"joint_state_controller", "j1_controller", "j2_controller"});
  }

  // sim_server in `mode` for sim_seconds of sim time; returns when it has stopped.
  void run_sim(double sim_seconds, const std::string& mode = "lockstep", std::vector<std::string> extra = {}) {
    ChildProcess sim(with({bin("sim_server"), "--urdf", urdf_, "--config", config_, "--mode", mode, "--duration",
                           std::to_string(sim_seconds)},
                          extra),
                     env());
    ASSERT_EQ(sim.wait(45), 0) << sim.output();
    sim_output_ = sim.output();
  }
  const std::string& sim_output() const { return sim_output_; }

  void shut_down() {
    if (spawner_) {
      EXPECT_EQ(spawner_->stop(10), 0) << spawner_->output();
    }
    if (cm_) {
      EXPECT_EQ(cm_->stop(10), 0) << cm_->output();
    }
  }

 private:
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
