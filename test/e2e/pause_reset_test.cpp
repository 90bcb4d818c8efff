// cmctl pause / resume / step / reset against the real sim_server and
// controller_manager: controllers spawned while paused, exact steps, a reset
// that restarts the controllers from the start pose without a jump, and in
// lockstep a run after a reset repeating the one before bit for bit, whichever
// way the two processes receive (--hardware-reader direct or lcm).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "test/e2e/session.hpp"
#include "test/support/lcm_test.hpp"

namespace lcm_control::testing {
namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// turret_bot with the tutorial's controllers spawned once sim_server is up, and a tap on the bus.
class Session : public RobotSession {
 public:
  Session() : RobotSession(source("config/turret_bot.urdf"), source("config/turret_bot.yaml")), lc(url()) {}

  // sim_extra goes to sim_server; cm_extra to controller_manager.
  void start(const std::vector<std::string>& sim_extra, const std::vector<std::string>& cm_extra = {}) {
    start_controller_manager(cm_extra);
    ASSERT_NO_FATAL_FAILURE(start_sim(sim_extra, 30));
    // The controllers start, and command sources begin, on the state the controller manager already follows: a
    // switch or a source that came before its first state would start at once and run at step 0, one step earlier
    // than after it (a loaded machine can hold the first state back past both).
    ASSERT_TRUE(cm_->wait_for_output("hardware session", 30)) << cm_output() << sim_output();
    spawn({"joint_state_controller", "j1_controller", "j2_controller"});
  }
  int cmctl(std::vector<std::string> args, std::string* out = nullptr) {
    args.insert(args.begin(), "cmctl");
    return run(args, out);
  }

  lcm::LCM lc;
};

// Positions and velocities of every actuator by step, from the states recorded since `from`.
std::map<int64_t, std::vector<double>> by_step(const std::vector<hardware_state_t>& states, size_t from) {
  std::map<int64_t, std::vector<double>> out;
  for (size_t k = from; k < states.size(); ++k) {
    std::vector<double> v = states[k].position;
    v.insert(v.end(), states[k].velocity.begin(), states[k].velocity.end());
    out.emplace(states[k].step, std::move(v));
  }
  return out;
}

TEST(PauseStepReset, LockstepSpawnsWhilePausedStepsExactlyAndRepeatsARunAfterAResetBitForBit) {
  Session s;
  Recorder<hardware_state_t> states(s.lc, "hardware/state");
  ASSERT_NO_FATAL_FAILURE(s.start({"--mode", "lockstep", "--paused"}));  // the spawner's switch answers while paused
  auto j1 = s.background({"turret-cmd", "--sim-time", "j1_controller", "0.5", "--rate", "60"});
  auto j2 = s.background({"turret-cmd", "--sim-time", "j2_controller", "3.14*sin(i/100)", "--rate", "60"});
  ASSERT_TRUE(j1->wait_for_output("turret-cmd: ", 30)) << j1->output();
  ASSERT_TRUE(j2->wait_for_output("turret-cmd: ", 30)) << j2->output();
  pump_until(s.lc, [] { return false; }, 0.3);
  ASSERT_FALSE(states.messages.empty());
  EXPECT_EQ(states.messages.back().step, 0);  // nothing stepped while the controllers were spawned

  std::string out;
  ASSERT_EQ(s.cmctl({"step", "1000"}, &out), 0) << out << s.sim_output();
  EXPECT_TRUE(has(out, "stepped 1000 control steps: paused at step 1000")) << out;
  ASSERT_TRUE(pump_until(s.lc, [&] { return states.messages.back().step == 1000; }, 5));  // what came meanwhile
  size_t mark = states.messages.size();
  pump_until(s.lc, [] { return false; }, 0.4);
  ASSERT_GT(states.messages.size(), mark + 2) << "a paused sim_server republishes its state";
  for (size_t k = mark; k < states.messages.size(); ++k) EXPECT_EQ(states.messages[k].step, 1000);

  std::vector<std::map<int64_t, std::vector<double>>> runs;
  for (int run = 0; run < 2; ++run) {
    ASSERT_EQ(s.cmctl({"reset"}, &out), 0) << out;
    EXPECT_TRUE(has(out, "reset at step") && has(out, "to step 0")) << out;
    ASSERT_TRUE(pump_until(s.lc, [&] { return states.messages.back().step == 0; }, 5));
    mark = states.messages.size() - 1;
    ASSERT_EQ(s.cmctl({"step", "1500"}, &out), 0) << out;
    ASSERT_TRUE(pump_until(s.lc, [&] { return states.messages.back().step == 1500; }, 5));
    runs.push_back(by_step(states.messages, mark));
    ASSERT_EQ(runs.back().size(), 1501u) << "every step 0..1500 once (lost on the bus?)";
    EXPECT_EQ(runs.back().at(0)[0], 0.0);  // the start pose
    EXPECT_NEAR(runs.back().at(1500)[0], 0.5, 0.02);  // j1 went to 0.5 again
  }
  for (int64_t k = 0; k <= 1500; ++k) ASSERT_EQ(runs[0].at(k), runs[1].at(k)) << "step " << k;  // bit for bit
  j1->stop(5);
  j2->stop(5);
  EXPECT_TRUE(has(s.cm_output(), "hardware step went back from 1500 to 0 (a reset)")) << s.cm_output();
  EXPECT_FALSE(has(s.sim_output(), "dropped a hardware/command")) << s.sim_output();
}

// The same scripted run (spawned while paused, inputs on the sim clock, 1,500 steps) with the hardware loop read on
// the loop threads, through LCM's receive thread, and over shared memory (every state mirrored to LCM for the
// recorder): the same trajectory bit for bit.
TEST(PauseStepReset, LockstepIsBitIdenticalWithEitherHardwareReaderAndOverSharedMemory) {
  std::vector<std::map<int64_t, std::vector<double>>> runs;
  for (const std::string way : {"direct", "lcm", "shm"}) {
    SCOPED_TRACE(way);
    Session s;
    Recorder<hardware_state_t> states(s.lc, "hardware/state");
    const std::string segment = "shm:pause-reset-" + std::to_string(getpid());
    std::vector<std::string> hw = {"--hardware-reader", way == "lcm" ? "lcm" : "direct"};
    if (way == "shm") hw.insert(hw.end(), {"--hardware-url", segment});
    std::vector<std::string> sim = {"--mode", "lockstep", "--paused"};
    sim.insert(sim.end(), hw.begin(), hw.end());
    if (way == "shm") sim.insert(sim.end(), {"--hardware-mirror", "1000000"});
    ASSERT_NO_FATAL_FAILURE(s.start(sim, hw));
    EXPECT_EQ(has(s.sim_output(), "hardware read directly"), way == "direct") << s.sim_output();
    EXPECT_EQ(has(s.sim_output(), "hardware loop on " + segment), way == "shm") << s.sim_output();
    std::vector<std::string> sim_time = {"--sim-time"};
    if (way == "shm") sim_time.insert(sim_time.end(), {"--hardware-url", segment});
    auto cmd = [&](const std::string& controller, const std::string& expr) {
      std::vector<std::string> argv = {"turret-cmd", controller, expr, "--rate", "60"};
      argv.insert(argv.end(), sim_time.begin(), sim_time.end());
      return s.background(argv);
    };
    auto j1 = cmd("j1_controller", "0.5");
    auto j2 = cmd("j2_controller", "3.14*sin(i/100)");
    ASSERT_TRUE(j1->wait_for_output("turret-cmd: ", 30)) << j1->output();
    ASSERT_TRUE(j2->wait_for_output("turret-cmd: ", 30)) << j2->output();
    std::string out;
    ASSERT_EQ(s.cmctl({"step", "1500"}, &out), 0) << out << s.sim_output();
    ASSERT_TRUE(pump_until(s.lc, [&] { return !states.messages.empty() && states.messages.back().step == 1500; }, 5));
    runs.push_back(by_step(states.messages, 0));
    ASSERT_EQ(runs.back().size(), 1501u) << "every step 0..1500 once (lost on the bus?)";
    EXPECT_NEAR(runs.back().at(1500)[0], 0.5, 0.02);
    EXPECT_FALSE(has(s.sim_output(), "dropped a hardware/command")) << s.sim_output();
  }
  for (size_t r = 1; r < runs.size(); ++r)
    for (int64_t k = 0; k <= 1500; ++k) ASSERT_EQ(runs[0].at(k), runs[r].at(k)) << "run " << r << ", step " << k;
}

TEST(PauseStepReset, RealTimePauseHoldsTimeSwitchesAndResetRestartsControllersWithoutAJump) {
  Session s;
  Recorder<hardware_state_t> states(s.lc, "hardware/state");
  Recorder<hardware_command_t> commands(s.lc, "hardware/command");
  // A watchdog of 0.5 s, shorter than the pause below (which must not trip it) and longer than a stall of a loaded
  // machine (which would).
  ASSERT_NO_FATAL_FAILURE(s.start({"--watchdog", "0.5"}));
  ASSERT_EQ(s.run({"turret-cmd", "j1_controller", "0.5"}), 0);
  ASSERT_TRUE(pump_until(
      s.lc, [&] { return !states.messages.empty() && std::abs(states.messages.back().position[0] - 0.5) < 0.01; }, 10));

  std::string out;
  ASSERT_EQ(s.cmctl({"pause"}, &out), 0) << out;
  const auto said = out.find("paused at step ");
  ASSERT_NE(said, std::string::npos) << out;
  const int64_t held = std::stoll(out.substr(said + 15));
  // From the first state of the paused step on (what came while cmctl ran is before it, however late this test
  // got to it), every state is that step, republished at 10 Hz.
  pump_until(s.lc, [] { return false; }, 0.8);
  size_t mark = 0;
  while (mark < states.messages.size() && states.messages[mark].step != held) ++mark;
  ASSERT_GE(states.messages.size(), mark + 3) << "republished at 10 Hz";
  for (size_t k = mark; k < states.messages.size(); ++k) EXPECT_EQ(states.messages[k].step, held);

  // Switching while paused: stop and start answer on the repeated state, at the paused step.
  ASSERT_EQ(s.cmctl({"stop", "j1_controller"}, &out), 0) << out;
  EXPECT_TRUE(has(out, "at step " + std::to_string(held))) << out;
  ASSERT_EQ(s.cmctl({"start", "j1_controller"}, &out), 0) << out;
  ASSERT_EQ(s.cmctl({"step", "5"}, &out), 0) << out;
  EXPECT_TRUE(has(out, "paused at step " + std::to_string(held + 5))) << out;
  EXPECT_EQ(s.cmctl({"step", "0"}, &out), 2) << out;  // a usage error
  ASSERT_EQ(s.cmctl({"resume"}, &out), 0) << out;
  mark = states.messages.size();
  pump_until(
      s.lc, [&] { return states.messages.size() > mark && states.messages.back().step > held + 200; }, 5.0);
  ASSERT_GT(states.messages.size(), mark);
  EXPECT_GT(states.messages.back().step, held + 200) << "running again";
  EXPECT_EQ(s.cmctl({"step", "5"}, &out), 1) << out;
  EXPECT_TRUE(has(out, "pause it first")) << out;

  // Reset to a new start pose: the position controller restarts holding it, not jumping back to its 0.5.
  ASSERT_EQ(s.cmctl({"reset", "-J", "j1=0.3"}, &out), 0) << out;
  EXPECT_TRUE(has(out, "j1=0.3")) << out;
  pump_until(s.lc, [] { return false; }, 0.5);
  const hardware_state_t* first = nullptr;
  for (const auto& st : states.messages)
    if (st.step == 0) first = &st;
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->position[0], 0.3);
  const hardware_command_t* answer = nullptr;
  for (const auto& c : commands.messages)
    if (c.step == 0 && c.session == first->session) answer = &c;
  ASSERT_NE(answer, nullptr);
  EXPECT_NEAR(answer->command[0], 0.3, 1e-9) << "the restarted j1_controller holds the measured position";
  EXPECT_LT(states.messages.back().step, 1000);
  EXPECT_NEAR(states.messages.back().position[0], 0.3, 0.01);

  EXPECT_EQ(s.cmctl({"reset", "-J", "j3=1"}, &out), 1) << out;
  EXPECT_TRUE(has(out, "did you mean 'j1'") && has(out, "nothing was changed")) << out;
  EXPECT_EQ(s.cmctl({"sim-status"}, &out), 0) << out;
  EXPECT_TRUE(has(out, "running at step") && has(out, "1 reset")) << out;
  EXPECT_FALSE(has(s.sim_output(), "dropped a hardware/command")) << s.sim_output();
  EXPECT_FALSE(has(s.sim_output(), "watchdog")) << s.sim_output();
}

}  // namespace
}  // namespace lcm_control::testing
