// End-to-end: the real controller_manager process on a per-test LCM URL,
// driven by the fake hardware (lockstep unless said otherwise) and talked to
// over LCM exactly as cmctl / spawner / turret-cmd would.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "bus/messages.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/controller_state_t.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/loop_stats_t.hpp"
#include "lcm_control/pid_gains_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"
#include "test/controller_manager/fake_hardware.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"
#include "description/load.hpp"

using namespace lcm_control;
using namespace lcm_control::testing;

namespace {

std::string data(const std::string& f) { return source("test/controller_manager/data/" + f); }
bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

RobotModel test_bot() { return load_robot_model(data("test_bot.urdf"), data("test_bot.yaml")); }

// A controller_manager process plus a client on the same fresh URL.
struct Session {
  explicit Session(const std::string& yaml = data("test_bot.yaml"), std::vector<std::string> extra = {},
                   const std::string& urdf = data("test_bot.urdf"))
      : url(unique_lcm_url()),
        proc([&] {
          std::vector<std::string> a{bin("controller_manager"), "--urdf", urdf, "--config", yaml, "--lcm-url", url};
          if (std::find(extra.begin(), extra.end(), "--silence-timeout") == extra.end())
            a.insert(a.end(), {"--silence-timeout", "0.25"});
          a.insert(a.end(), extra.begin(), extra.end());
          return a;
        }()),
        lc(url),
        responses(lc, prefix(extra) + "controller_manager/response") {
    ready = proc.wait_for_output("ready (", 10);
  }
  static std::string prefix(const std::vector<std::string>& extra) {
    for (size_t k = 0; k + 1 < extra.size(); ++k)
      if (extra[k] == "--namespace") return extra[k + 1] + "/";
    return "";
  }

  cm_response_t call(int8_t op, std::vector<std::string> names = {}, std::vector<std::string> start = {},
                     std::vector<std::string> stop = {}, int8_t strictness = cm_request_t::STRICT,
                     const std::string& ns = "") {
    cm_request_t r = cm_request(op, names, start, stop, strictness);
    r.request_id = next_id++;
    r.client = "e2e_test";
    lc.publish(ns + "controller_manager/request", &r);
    return wait_response(r.request_id);
  }
  cm_response_t wait_response(int64_t id) {
    const cm_response_t* found = nullptr;
    pump_until(
        lc,
        [&] {
          for (const auto& m : responses.messages)
            if (m.request_id == id) found = &m;
          return found != nullptr;
        },
        10.0);
    if (!found) {
      ADD_FAILURE() << "no response to request " << id << "\n" << proc.output();
      return cm_response_t{};
    }
    return *found;
  }
  cm_response_t load_and_start(std::vector<std::string> names) {
    for (const auto& n : names) {
      const auto r = call(cm_request_t::LOAD, {n});
      EXPECT_TRUE(r.ok) << r.message;
    }
    const auto s = call(cm_request_t::SWITCH, {}, names);
    EXPECT_TRUE(s.ok) << s.message;
    return s;
  }
  void command(const std::string& controller, double v) {
    float64_t m{};
    m.data = v;
    lc.publish(controller + "/command", &m);
  }
  void command(const std::string& controller, std::vector<double> v) {
    float64_array_t m{};
    m.size = static_cast<int32_t>(v.size());
    m.data = v;
    lc.publish(controller + "/command", &m);
  }

  std::string url;
  ChildProcess proc;
  lcm::LCM lc;
  Recorder<cm_response_t> responses;
  int64_t next_id = 1;
  bool ready = false;
};

joint_trajectory_t three_waypoints(int64_t id) {
  joint_trajectory_t g{};
  g.goal_id = id;
  g.joint_names = {"tilt", "slide"};
  g.num_joints = 2;
  for (auto [t, a, b] : {std::tuple{0.4, 0.5, 0.2}, {0.8, -0.3, 0.7}, {1.2, 0.2, 0.4}}) {
    trajectory_point_t p{};
    p.time_from_start = t;
    p.positions = {a, b};
    p.num_positions = 2;
    g.points.push_back(p);
  }
  g.num_points = 3;
  return g;
}

// joint_states on the wall clock: 60 Hz +/- 5% while the hardware keeps real
// time; an overloaded machine that slows the hardware itself is reported, not failed.
void expect_wall_rate(double rate, double real_time_factor) {
  if (std::abs(real_time_factor - 1.0) > 0.03) {
    std::printf("note: the hardware ran at %.3f x real time (machine overloaded); wall rate %.2f Hz not checked\n",
                real_time_factor, rate);
    return;
  }
  EXPECT_NEAR(rate, 60.0, 3.0) << "real-time factor " << real_time_factor;
}

size_t index_of(const std::vector<FakeActuator>& a, const std::string& name) {
  for (size_t k = 0; k < a.size(); ++k)
    if (a[k].name == name) return k;
  return SIZE_MAX;
}

}  // namespace

TEST(ControllerManagerE2E, ServicesAnswerWithoutHardwareAndSwitchAtOnce) {
  Session s;
  ASSERT_TRUE(s.ready) << s.proc.output();
  auto r = s.call(cm_request_t::LIST_TYPES);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.num_types, 37);
  r = s.call(cm_request_t::LOAD, {"slide_position", "joint_state_controller"});
  ASSERT_TRUE(r.ok) << r.message;
  r = s.call(cm_request_t::SWITCH, {}, {"slide_position", "joint_state_controller"});
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(has(r.message, "switched at once (no hardware state received yet)")) << r.message;
  r = s.call(cm_request_t::LIST);
  ASSERT_EQ(r.num_controllers, 2);
  EXPECT_EQ(r.controllers[0].name, "slide_position");
  EXPECT_EQ(r.controllers[0].state, "running");
  EXPECT_EQ(r.controllers[0].type, "position_controllers/JointPositionController");
  EXPECT_EQ(r.controllers[0].hardware_interface, "PositionJointInterface");
  EXPECT_EQ(r.controllers[0].joints, std::vector<std::string>{"slide"});
  EXPECT_EQ(r.controllers[1].hardware_interface, "");
  // Configuration mistakes are reported at start, before anyone tries to load them.
  const std::string out = s.proc.output();
  EXPECT_TRUE(has(out, "configured controller will not load: " + data("test_bot.yaml") +
                           ": typo_type/type: controller type 'position_controllers/JointPositionControler' does not "
                           "exist; did you mean 'position_controllers/JointPositionController'?"))
      << out;
  EXPECT_TRUE(has(out, "will not load: controller 'wrong_interface' needs VelocityJointInterface")) << out;
  EXPECT_TRUE(has(out, "will not load: controller 'missing_joint': joint 'elbow' is not in the URDF")) << out;
  EXPECT_TRUE(has(out, "will not load: " + data("test_bot.yaml") + ": no_publish_rate/publish_rate: missing")) << out;
}

TEST(ControllerManagerE2E, NamespacePrefixesEveryChannel) {
  Session s(data("test_bot.yaml"), {"--namespace", "robot1"});
  ASSERT_TRUE(s.ready) << s.proc.output();
  FakeHardwareOptions o;
  o.ns = "robot1";
  FakeHardware hw(s.url, actuators_for(test_bot()), o);
  hw.start();
  ASSERT_TRUE(hw.run_steps(10, 10));  // ticking: the command below is not lost to the first-state restart
  auto r = s.call(cm_request_t::LOAD, {"slide_position"}, {}, {}, 2, "robot1/");
  ASSERT_TRUE(r.ok) << r.message;
  r = s.call(cm_request_t::SWITCH, {}, {"slide_position"}, {}, 2, "robot1/");
  ASSERT_TRUE(r.ok) << r.message;
  s.command("robot1/slide_position", 0.4);
  ASSERT_TRUE(hw.run_steps(200, 10));
  EXPECT_DOUBLE_EQ(hw.actuator("slide_motor").position, 0.4);
}

TEST(ControllerManagerE2E, ForwardControllersMoveTheirJoints) {
  Session s;
  ASSERT_TRUE(s.ready) << s.proc.output();
  FakeHardware hw(s.url, actuators_for(test_bot()));
  hw.start();
  ASSERT_TRUE(hw.run_steps(10, 10));
  s.load_and_start({"slide_position", "wheel_velocity", "arm_effort"});
  s.command("slide_position", 0.7);
  s.command("wheel_velocity", 2.0);
  s.command("arm_effort", 5.0);
  ASSERT_TRUE(hw.run_steps(300, 10));
  EXPECT_DOUBLE_EQ(hw.actuator("slide_motor").position, 0.7);
  EXPECT_DOUBLE_EQ(hw.actuator("wheel_motor").velocity, 20.0);  // 2 rad/s through reduction 10
  EXPECT_DOUBLE_EQ(hw.actuator("arm_motor").effort, 5.0);
  EXPECT_GT(hw.actuator("arm_motor").velocity, 1.0);
  EXPECT_EQ(hw.dropped(), 0);
}

TEST(ControllerManagerE2E, GroupControllersMoveTheirJointsAndWrongSizesAreCounted) {
  Session s;
  ASSERT_TRUE(s.ready) << s.proc.output();
  Recorder<loop_stats_t> stats(s.lc, "controller_manager/statistics");
  FakeHardware hw(s.url, actuators_for(test_bot()));
  hw.start();
  ASSERT_TRUE(hw.run_steps(10, 10));
  s.load_and_start({"pos_group", "vel_group", "eff_group"});
  s.command("pos_group", std::vector<double>{0.3, -0.5});
  s.command("vel_group", std::vector<double>{1.0, -2.0});
  s.command("eff_group", std::vector<double>{3.0, 4.0});
  ASSERT_TRUE(hw.run_steps(200, 10));
  s.command("pos_group", std::vector<double>{0.9});
  ASSERT_TRUE(hw.run_steps(200, 10));
  EXPECT_DOUBLE_EQ(hw.actuator("slide_motor").position, 0.3);
  EXPECT_DOUBLE_EQ(hw.actuator("tilt_motor").position, -0.5);
  EXPECT_DOUBLE_EQ(hw.actuator("wheel_motor").velocity, 10.0);
  EXPECT_DOUBLE_EQ(hw.actuator("roll_motor").velocity, -2.0);
  EXPECT_DOUBLE_EQ(hw.actuator("spin_motor").effort, 3.0);
  EXPECT_DOUBLE_EQ(hw.actuator("arm_motor").effort, 4.0);
  int64_t dropped = 0;
  const loop_stats_t* last = nullptr;
  pump_until(
      s.lc,
      [&] {
        dropped = 0;
        for (const auto& m : stats.messages) dropped += m.dropped, last = &m;
        return dropped >= 1 && last->cycles > 0;
      },
      3.0);
  EXPECT_EQ(dropped, 1);
  ASSERT_NE(last, nullptr);
  EXPECT_EQ(last->process, "controller_manager");
  EXPECT_EQ(last->item, (std::vector<std::string>{"pos_group", "vel_group", "eff_group"}));
  EXPECT_GT(last->period_mean_us, 0);
  EXPECT_GT(last->exec_mean_us, 0);
  EXPECT_TRUE(has(s.proc.output(), "pos_group: dropped a command: 1 values for 2 joints")) << s.proc.output();
}

TEST(ControllerManagerE2E, EffortPositionControllerHoldsAGravityLoadedJoint) {
  Session s;
  ASSERT_TRUE(s.ready) << s.proc.output();
  auto act = actuators_for(test_bot());
  auto& arm = find_actuator(act, "arm_motor");
  arm.gravity = 10.0;  // N*m at horizontal
  arm.inertia = 0.2;
  arm.position = 0.5;
  const size_t a = index_of(act, "arm_motor");
  FakeHardware hw(s.url, act);
  hw.pause(true);
  hw.start();
  const auto r = s.load_and_start({"arm_position"});  // before the hardware: no sag while nobody holds it
  hw.pause(false);
  ASSERT_TRUE(hw.run_steps(2000, 20));
  double worst = 0;
  int n = 0;
  for (const auto& rec : hw.records()) {
    worst = std::max(worst, std::abs(rec.position[a] - 0.5));
    ++n;
  }
  EXPECT_GE(n, 2000);
  EXPECT_LT(worst, 0.01) << "hold error";
  std::printf("gravity hold: worst |error| %.6f rad over %d steps (limit 0.01)\n", worst, n);
  s.command("arm_position", 1.0);
  ASSERT_TRUE(hw.run_steps(2000, 20));
  EXPECT_NEAR(hw.actuator("arm_motor").position, 1.0, 0.01);
}

TEST(ControllerManagerE2E, PidControllersFollowTheirSetPointsWithStateAndGains) {
  Session s;
  ASSERT_TRUE(s.ready) << s.proc.output();
  Recorder<controller_state_t> state(s.lc, "spin_velocity/state");
  Recorder<pid_gains_t> gains(s.lc, "wheel_position/gains");
  auto act = actuators_for(test_bot());
  find_actuator(act, "spin_motor").inertia = 0.1;
  find_actuator(act, "wheel_motor").position = (0.2 - 0.5) * 10;  // wheel joint at 0.2 rad
  FakeHardware hw(s.url, act);
  hw.start();
  ASSERT_TRUE(hw.run_steps(10, 10));
  s.load_and_start({"spin_velocity", "wheel_position"});
  s.command("spin_velocity", 3.0);
  s.command("wheel_position", 2 * M_PI - 0.2);  // continuous: the short way is -0.4 rad
  ASSERT_TRUE(hw.run_steps(3000, 20));
  EXPECT_NEAR(hw.actuator("spin_motor").velocity, 3.0, 0.05);
  const double wheel = hw.actuator("wheel_motor").position / 10 + 0.5;
  EXPECT_NEAR(wheel, -0.2, 0.01);
  pump_until(
      s.lc, [&] { return state.messages.size() > 5; }, 2.0);
  ASSERT_FALSE(state.messages.empty());
  EXPECT_EQ(state.messages.back().controller, "spin_velocity");
  EXPECT_DOUBLE_EQ(state.messages.back().set_point, 3.0);

  pid_gains_t q{};
  q.request_id = 5;
  q.query = true;
  s.lc.publish("wheel_position/gains/set", &q);
  pid_gains_t set{};
  set.request_id = 6;
  set.joint = "wheel";
  set.p = 20;
  s.lc.publish("wheel_position/gains/set", &set);
  ASSERT_TRUE(pump_until(
      s.lc, [&] { return gains.messages.size() >= 2; }, 5.0));
  EXPECT_EQ(gains.messages[0].request_id, 5);
  EXPECT_EQ(gains.messages[0].p, 10);
  EXPECT_TRUE(gains.messages[1].ok) << gains.messages[1].message;
  EXPECT_EQ(gains.messages[1].p, 20);
}

TEST(ControllerManagerE2E, TrajectoryFollowsWithinToleranceThenFailsWhenItIsImpossible) {
  Session s;
  ASSERT_TRUE(s.ready) << s.proc.output();
  Recorder<trajectory_status_t> result(s.lc, "trajectory/result");
  Recorder<trajectory_status_t> feedback(s.lc, "trajectory/feedback");
  Recorder<trajectory_status_t> tight(s.lc, "trajectory_tight/result");
  FakeHardware hw(s.url, actuators_for(test_bot()));
  hw.start();
  ASSERT_TRUE(hw.run_steps(10, 10));
  s.load_and_start({"trajectory"});
  auto g = three_waypoints(1);
  s.lc.publish("trajectory/command", &g);
  ASSERT_TRUE(pump_until(
      s.lc, [&] { return !result.messages.empty(); }, 20.0))
      << s.proc.output();
  const auto& r = result.messages[0];
  EXPECT_EQ(r.status, trajectory_status_t::SUCCEEDED) << r.message << "\n" << s.proc.output();
  std::printf("trajectory: %s\n", r.message.c_str());
  double worst = 0;
  for (const auto& f : feedback.messages)
    for (double e : f.error) worst = std::max(worst, std::abs(e));
  EXPECT_LT(worst, 0.05);  // the path tolerance
  EXPECT_GE(feedback.messages.size(), 20u);
  ASSERT_TRUE(hw.run_steps(5, 10));  // the result can overtake the last command
  std::printf("trajectory: worst feedback error %.6f over %zu feedback messages (tolerance 0.05)\n", worst,
              feedback.messages.size());
  EXPECT_NEAR(hw.actuator("tilt_motor").position, 0.2, 1e-9);
  EXPECT_NEAR(hw.actuator("slide_motor").position, 0.4, 1e-9);

  ASSERT_TRUE(s.call(cm_request_t::LOAD, {"trajectory_tight"}).ok);
  const auto sw = s.call(cm_request_t::SWITCH, {}, {"trajectory_tight"}, {"trajectory"});
  ASSERT_TRUE(sw.ok) << sw.message;
  g = three_waypoints(2);
  s.lc.publish("trajectory_tight/command", &g);
  ASSERT_TRUE(pump_until(
      s.lc, [&] { return !tight.messages.empty(); }, 20.0))
      << s.proc.output();
  const auto& t = tight.messages[0];
  EXPECT_EQ(t.status, trajectory_status_t::PATH_TOLERANCE_VIOLATED) << t.message;
  EXPECT_TRUE(has(t.message, "path tolerance violated on joint '")) << t.message;
  EXPECT_TRUE(has(t.message, "exceeds 0.000001")) << t.message;
  std::printf("tight trajectory: %s\n", t.message.c_str());
}

TEST(ControllerManagerE2E, EffortTrajectoryControllerTracksAGravityLoadedJoint) {
  Session s;
  ASSERT_TRUE(s.ready) << s.proc.output();
  Recorder<trajectory_status_t> result(s.lc, "effort_trajectory/result");
  auto act = actuators_for(test_bot());
  find_actuator(act, "arm_motor").gravity = 10.0;
  find_actuator(act, "arm_motor").inertia = 0.2;
  find_actuator(act, "spin_motor").inertia = 0.1;
  FakeHardware hw(s.url, act);
  hw.pause(true);
  hw.start();
  s.load_and_start({"effort_trajectory"});
  hw.pause(false);
  ASSERT_TRUE(hw.run_steps(10, 10));
  joint_trajectory_t g{};
  g.goal_id = 3;
  g.joint_names = {"spin", "arm"};
  g.num_joints = 2;
  for (auto [t, spin, arm] : {std::tuple{1.0, 1.0, 0.5}, {2.0, 3.0, 1.0}, {3.0, 6.0, 0.8}}) {
    trajectory_point_t p{};
    p.time_from_start = t;
    p.positions = {spin, arm};
    p.num_positions = 2;
    g.points.push_back(p);
  }
  g.num_points = 3;
  s.lc.publish("effort_trajectory/command", &g);
  ASSERT_TRUE(pump_until(
      s.lc, [&] { return !result.messages.empty(); }, 30.0))
      << s.proc.output();
  EXPECT_EQ(result.messages[0].status, trajectory_status_t::SUCCEEDED) << result.messages[0].message;
  std::printf("effort trajectory: %s\n", result.messages[0].message.c_str());
  EXPECT_NEAR(hw.actuator("arm_motor").position, 0.8, 0.02);
}

TEST(ControllerManagerE2E, JointStatesAtPublishRateInTransmissionOrder) {
  Session s;
  ASSERT_TRUE(s.ready) << s.proc.output();
  FakeHardwareOptions o;
  o.lockstep = false;  // 1 kHz on the wall clock, like sim_server in real time
  FakeHardware hw(s.url, actuators_for(test_bot()), o);
  hw.start();
  s.load_and_start({"joint_state_controller"});
  Recorder<joint_state_t> js(s.lc, "joint_states");
  pump_until(
      s.lc, [] { return false; }, 2.0);
  ASSERT_GT(js.messages.size(), 10u);
  const double wall = (js.arrival_us.back() - js.arrival_us.front()) * 1e-6;
  const double hw_time = (js.messages.back().utime - js.messages.front().utime) * 1e-6;
  const double rate_wall = (js.messages.size() - 1) / wall, rate_hw = (js.messages.size() - 1) / hw_time;
  std::printf("joint_states: %zu messages, %.2f Hz on the wall clock, %.2f Hz on the hardware clock\n",
              js.messages.size(), rate_wall, rate_hw);
  EXPECT_NEAR(rate_hw, 60.0, 3.0);
  expect_wall_rate(rate_wall, hw_time / wall);
  EXPECT_EQ(js.messages[0].name, (std::vector<std::string>{"tilt", "slide", "arm", "wheel", "spin", "roll"}));
}

TEST(ControllerManagerE2E, RefusalsAreSpecificAndTheLoopKeepsRunning) {
  Session s;
  ASSERT_TRUE(s.ready) << s.proc.output();
  FakeHardware hw(s.url, actuators_for(test_bot()));
  hw.start();
  s.load_and_start({"slide_position"});
  auto keeps_running = [&] {
    EXPECT_TRUE(hw.run_steps(50, 10)) << "the loop stopped";
    EXPECT_TRUE(s.proc.running());
  };
  // Unknown type: valid types and the closest one.
  auto r = s.call(cm_request_t::LOAD, {"typo_type"});
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message,
                  "typo_type/type: controller type 'position_controllers/JointPositionControler' does "
                  "not exist; did you mean 'position_controllers/JointPositionController'? Valid types: "))
      << r.message;
  keeps_running();
  // Interface mismatch.
  r = s.call(cm_request_t::LOAD, {"wrong_interface"});
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message,
                  "controller 'wrong_interface' needs VelocityJointInterface on joint 'slide', but "
                  "transmission 't_slide' offers only PositionJointInterface"))
      << r.message;
  keeps_running();
  // Claim conflict, whatever the strictness.
  ASSERT_TRUE(s.call(cm_request_t::LOAD, {"pos_group"}).ok);
  for (int8_t strictness : {cm_request_t::STRICT, cm_request_t::BEST_EFFORT}) {
    r = s.call(cm_request_t::SWITCH, {}, {"pos_group"}, {}, strictness);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(has(r.message, "controllers 'slide_position' and 'pos_group' would both claim joint 'slide'"))
        << r.message;
  }
  keeps_running();
  // Unloading a running controller.
  r = s.call(cm_request_t::UNLOAD, {"slide_position"});
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "cannot unload 'slide_position': it is running; stop it first")) << r.message;
  keeps_running();
  // Malformed requests: bytes that are not a cm_request_t, an unknown op, a load without names.
  const char junk[] = "this is not a cm_request_t";
  s.lc.publish("controller_manager/request", junk, sizeof junk);
  r = s.wait_response(-1);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message,
                  "malformed request: could not decode 27 bytes on 'controller_manager/request' as "
                  "cm_request_t"))
      << r.message;
  r = s.call(42);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "malformed request: unknown op 42")) << r.message;
  r = s.call(cm_request_t::LOAD);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "malformed request: load needs at least one controller name")) << r.message;
  keeps_running();
  r = s.call(cm_request_t::LIST);
  ASSERT_EQ(r.num_controllers, 2);
  EXPECT_EQ(r.controllers[0].state, "running");
  EXPECT_EQ(r.controllers[1].state, "initialized");
}

TEST(ControllerManagerE2E, SwitchStopAStartBOnOneJointInOneCycle) {
  // The hardware counts as silent after 2 s, not 0.25: a stall of a loaded machine must not turn the one-cycle
  // switch into one done at once.
  Session s(data("test_bot.yaml"), {"--silence-timeout", "2"});
  ASSERT_TRUE(s.ready) << s.proc.output();
  auto act = actuators_for(test_bot());
  const size_t a = index_of(act, "arm_motor");
  FakeHardware hw(s.url, act);
  hw.start();
  ASSERT_TRUE(hw.run_steps(10, 10));
  ASSERT_TRUE(s.call(cm_request_t::LOAD, {"arm_position"}).ok);
  s.load_and_start({"arm_effort"});
  s.command("arm_effort", 3.0);
  ASSERT_TRUE(hw.run_steps(100, 10));
  const auto r = s.call(cm_request_t::SWITCH, {}, {"arm_position"}, {"arm_effort"});
  ASSERT_TRUE(r.ok) << r.message;
  const auto pos = r.message.find("at step ");
  ASSERT_NE(pos, std::string::npos) << r.message;
  const int64_t k = std::stoll(r.message.substr(pos + 8));
  ASSERT_TRUE(hw.run_steps(100, 10));
  const auto records = hw.records();
  int64_t first_a = -1, last_a = -1, first_b = -1, none_after_start = 0;
  for (const auto& rec : records) {
    const bool a_cmd = rec.mode[a] == hardware_command_t::MODE_EFFORT && rec.command[a] == 3.0;
    if (a_cmd && first_a < 0) first_a = rec.step;
    if (a_cmd) last_a = rec.step;
    if (!a_cmd && first_a >= 0 && first_b < 0) first_b = rec.step;
    if (first_a >= 0 && rec.mode[a] != hardware_command_t::MODE_EFFORT) ++none_after_start;
  }
  EXPECT_EQ(none_after_start, 0) << "a cycle where nobody commanded the arm";
  EXPECT_EQ(last_a, k) << r.message;       // A's command is the last one written in the switching cycle
  EXPECT_EQ(first_b, k + 1) << r.message;  // B's from the next
  for (const auto& rec : records) {
    if (rec.step > first_a && rec.step <= k) {
      EXPECT_EQ(rec.command[a], 3.0) << rec.step;
    }
  }
  std::printf("switch: arm_effort commanded steps %lld..%lld, arm_position from %lld (%s)\n",
              static_cast<long long>(first_a), static_cast<long long>(last_a), static_cast<long long>(first_b),
              r.message.c_str());
}

TEST(ControllerManagerE2E, SilenceIsReportedAndANewSessionRestartsFromTheCurrentState) {
  Session s;
  ASSERT_TRUE(s.ready) << s.proc.output();
  FakeHardware hw(s.url, actuators_for(test_bot()));
  hw.start();
  ASSERT_TRUE(hw.run_steps(10, 10));
  s.load_and_start({"slide_position"});
  s.command("slide_position", 0.6);
  ASSERT_TRUE(hw.run_steps(100, 10));
  EXPECT_DOUBLE_EQ(hw.actuator("slide_motor").position, 0.6);
  hw.pause(true);
  EXPECT_TRUE(s.proc.wait_for_output("no hardware/state for", 3)) << s.proc.output();
  // A simulator restart: new session, time 0, the slide back at 0.2. It must stay there.
  hw.set_position("slide_motor", 0.2);
  hw.restart_session();
  hw.pause(false);
  ASSERT_TRUE(hw.run_steps(100, 10));
  EXPECT_DOUBLE_EQ(hw.actuator("slide_motor").position, 0.2);
  EXPECT_TRUE(s.proc.wait_for_output("restart from the current state", 3)) << s.proc.output();
  s.command("slide_position", 0.8);
  ASSERT_TRUE(hw.run_steps(100, 10));
  EXPECT_DOUBLE_EQ(hw.actuator("slide_motor").position, 0.8);
}

// A sweep against one controller manager: a simulator started right after another ended sends its first state
// while the ended one still counts as alive. It is answered as soon as that one falls silent (the silence timeout),
// not when it next republishes (here after 10 s), its controllers start from its own state, and no second
// simulator is reported.
TEST(ControllerManagerE2E, ASessionStartedRightAfterAnotherEndedIsAnsweredAtTheSilenceTimeout) {
  Session s(data("test_bot.yaml"), {"--silence-timeout", "0.5"});
  ASSERT_TRUE(s.ready) << s.proc.output();
  {
    FakeHardware first(s.url, actuators_for(test_bot()));
    first.start();
    ASSERT_TRUE(first.run_steps(10, 10));
    s.load_and_start({"slide_position"});
    s.command("slide_position", 0.6);
    ASSERT_TRUE(first.run_steps(100, 10));
    EXPECT_DOUBLE_EQ(first.actuator("slide_motor").position, 0.6);
  }
  FakeHardwareOptions slow;
  slow.republish_s = 10;
  auto actuators = actuators_for(test_bot());
  find_actuator(actuators, "slide_motor").position = 0.2;
  FakeHardware second(s.url, actuators, slow);
  const auto started = std::chrono::steady_clock::now();
  second.start();
  ASSERT_TRUE(second.run_steps(100, 5)) << s.proc.output();
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  EXPECT_LT(waited, 3.0) << s.proc.output();
  EXPECT_TRUE(s.proc.wait_for_output("answering hardware session", 3)) << s.proc.output();
  // Not two simulators at once: the first never spoke again.
  EXPECT_FALSE(has(s.proc.output(), "two hardware sessions")) << s.proc.output();
  EXPECT_TRUE(s.proc.wait_for_output("restart from the current state", 3)) << s.proc.output();
  EXPECT_DOUBLE_EQ(second.actuator("slide_motor").position, 0.2);
  std::printf("the second session stepped 100 times %.2f s after it started (silence timeout 0.5 s)\n", waited);
}

// Other traffic must not hide a dead simulator: with a controller's commands arriving at 60 Hz (a turret-cmd),
// silence is still measured from the last hardware/state (issue 18: only a bus quiet for 20 ms was checked).
TEST(ControllerManagerE2E, SilenceIsReportedWhileOtherMessagesKeepComing) {
  Session s;
  ASSERT_TRUE(s.ready) << s.proc.output();
  FakeHardware hw(s.url, actuators_for(test_bot()));
  hw.start();
  ASSERT_TRUE(hw.run_steps(10, 10));
  s.load_and_start({"slide_position"});
  hw.pause(true);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  bool reported = false;
  while (!reported && std::chrono::steady_clock::now() < until) {
    s.command("slide_position", 0.3);
    std::this_thread::sleep_for(std::chrono::milliseconds(16));
    reported = s.proc.output().find("no hardware/state for") != std::string::npos;
  }
  EXPECT_TRUE(reported) << s.proc.output();
  hw.pause(false);
  ASSERT_TRUE(hw.run_steps(50, 10));
  EXPECT_TRUE(s.proc.wait_for_output("hardware/state resumed", 3)) << s.proc.output();
}

TEST(ControllerManagerE2E, CleanShutdownStopsAndUnloadsEverything) {
  Session s;
  ASSERT_TRUE(s.ready) << s.proc.output();
  FakeHardware hw(s.url, actuators_for(test_bot()));
  hw.start();
  s.load_and_start({"joint_state_controller", "slide_position"});
  ASSERT_TRUE(s.call(cm_request_t::LOAD, {"tilt_position"}).ok);
  ASSERT_TRUE(hw.run_steps(20, 10));
  EXPECT_EQ(s.proc.stop(5.0, SIGTERM), 0) << s.proc.output();
  EXPECT_TRUE(has(s.proc.output(),
                  "shutting down: stopped [joint_state_controller, slide_position], unloaded "
                  "[joint_state_controller, slide_position, tilt_position]"))
      << s.proc.output();
}

TEST(ControllerManagerE2E, BadInputExitsNonZeroWithOneClearLine) {
  const std::string dir = temp_dir("cm_bad");
  { std::ofstream(dir + "/broken.yaml") << "j1_controller: {type: [unclosed\n"; }
  ChildProcess missing({bin("controller_manager"), "--urdf", data("test_bot.urdf"), "--config", dir + "/nope.yaml",
                        "--lcm-url", unique_lcm_url()});
  EXPECT_EQ(missing.wait(10), 3);
  EXPECT_TRUE(has(missing.output(), "controller_manager: error: " + dir + "/nope.yaml: config file not found"))
      << missing.output();
  ChildProcess empty({bin("controller_manager"), "--urdf", data("test_bot.urdf"), "--config", "", "--lcm-url",
                      unique_lcm_url()});
  EXPECT_EQ(empty.wait(10), 3);
  EXPECT_TRUE(has(empty.output(), "controller_manager: error: the config file's path is empty (give one with --config)"))
      << empty.output();
  ChildProcess broken({bin("controller_manager"), "--urdf", data("test_bot.urdf"), "--config", dir + "/broken.yaml",
                       "--lcm-url", unique_lcm_url()});
  EXPECT_EQ(broken.wait(10), 3);
  EXPECT_TRUE(has(broken.output(), "broken.yaml:")) << broken.output();
  EXPECT_TRUE(has(broken.output(), "malformed YAML")) << broken.output();
  ChildProcess no_flags({bin("controller_manager"), "--config", data("test_bot.yaml")});
  EXPECT_NE(no_flags.wait(10), 0);
  EXPECT_TRUE(has(no_flags.output(), "--urdf")) << no_flags.output();
  ChildProcess bad_url({bin("controller_manager"), "--urdf", data("test_bot.urdf"), "--config", data("test_bot.yaml"),
                        "--lcm-url", "foo://bar"});
  EXPECT_EQ(bad_url.wait(10), 4);
  std::filesystem::remove_all(dir);
}

// The tutorial robot against the real sim_server in real time (skipped when
// sim_server is not part of the build).
TEST(ControllerManagerWithSimServer, TurretTutorialMovesAndPublishesJointStatesAt60Hz) {
#ifndef LCM_CONTROL_HAVE_SIM_SERVER
  GTEST_SKIP() << "sim_server is not built";
#else
  Session s(source("config/turret_bot.yaml"), {}, source("config/turret_bot.urdf"));
  ASSERT_TRUE(s.ready) << s.proc.output();
  ChildProcess sim({bin("sim_server"), "--urdf", source("config/turret_bot.urdf"), "--config",
                    source("config/turret_bot.yaml"), "--lcm-url", s.url});
  ASSERT_TRUE(sim.wait_for_output("ready (", 10)) << sim.output();
  s.load_and_start({"joint_state_controller", "j1_controller", "j2_controller"});
  Recorder<joint_state_t> js(s.lc, "joint_states");
  s.command("j1_controller", 0.5);
  s.command("j2_controller", 1.0);
  pump_until(
      s.lc, [] { return false; }, 3.0);
  ASSERT_GT(js.messages.size(), 100u) << s.proc.output() << sim.output();
  const double wall = (js.arrival_us.back() - js.arrival_us.front()) * 1e-6;
  const double rate = (js.messages.size() - 1) / wall;
  const double hw_time = (js.messages.back().utime - js.messages.front().utime) * 1e-6;
  EXPECT_NEAR((js.messages.size() - 1) / hw_time, 60.0, 3.0);
  std::printf("turret with sim_server: joint_states %.2f Hz over %zu messages; j1 %.4f (cmd 0.5), j2 %.4f (cmd 1.0)\n",
              rate, js.messages.size(), js.messages.back().position[0], js.messages.back().position[1]);
  expect_wall_rate(rate, hw_time / wall);
  EXPECT_EQ(js.messages.back().name, (std::vector<std::string>{"j1", "j2"}));
  EXPECT_NEAR(js.messages.back().position[0], 0.5, 0.1);
  EXPECT_NEAR(js.messages.back().position[1], 1.0, 0.2);
  EXPECT_EQ(s.proc.stop(5.0, SIGINT), 0);
  EXPECT_EQ(sim.stop(5.0, SIGINT), 0);
#endif
}

namespace {
// CPU time (user + system) of a process so far, in seconds.
double cpu_seconds(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::istringstream rest(text.substr(text.rfind(')') + 2));  // after the command name, which may hold spaces
  std::string field;
  double utime = 0, stime = 0;
  for (int k = 3; k <= 15 && rest >> field; ++k) {
    if (k == 14) utime = std::stod(field);
    if (k == 15) stime = std::stod(field);
  }
  return (utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}
}  // namespace

TEST(ControllerManagerWithSimServer, SpinningAnswersEveryStateSleepsBetweenThemAndBothReportTheirPeriodError) {
#ifndef LCM_CONTROL_HAVE_SIM_SERVER
  GTEST_SKIP() << "sim_server is not built";
#else
  Session s(source("config/turret_bot.yaml"), {"--spin-us", "150"}, source("config/turret_bot.urdf"));
  ASSERT_TRUE(s.ready) << s.proc.output();
  EXPECT_TRUE(has(s.proc.output(), "spinning 150 us around each real-time state")) << s.proc.output();
  ChildProcess sim({bin("sim_server"), "--urdf", source("config/turret_bot.urdf"), "--config",
                    source("config/turret_bot.yaml"), "--lcm-url", s.url, "--spin-us", "150"});
  ASSERT_TRUE(sim.wait_for_output("ready (", 10)) << sim.output();
  s.load_and_start({"joint_state_controller", "j1_controller", "j2_controller"});
  Recorder<loop_stats_t> cm_stats(s.lc, "controller_manager/statistics");
  Recorder<loop_stats_t> sim_stats(s.lc, "sim_server/statistics");
  Recorder<joint_state_t> js(s.lc, "joint_states");
  s.command("j1_controller", 0.5);
  const double cpu0 = cpu_seconds(s.proc.pid());
  const auto t0 = std::chrono::steady_clock::now();
  pump_until(
      s.lc, [] { return false; }, 3.0);
  const double cm_cpu = (cpu_seconds(s.proc.pid()) - cpu0) /
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("controller_manager --spin-us 150: %.0f %% of a core\n", cm_cpu * 100);
  // Spinning is for the tail before each state, not the whole period (it would take the whole core).
  EXPECT_LT(cm_cpu, 0.6);
  ASSERT_FALSE(js.messages.empty()) << s.proc.output() << sim.output();
  EXPECT_NEAR(js.messages.back().position[0], 0.5, 0.1);
  // Every window: the controller manager ran its loop on the real-time states and both ends give their period error
  // against the 1 ms period, within the extremes they report.
  // The first window each recorder got may have begun before the states did (the windows run from each process's
  // start), so the ones after it are judged.
  for (const auto* rec : {&cm_stats, &sim_stats}) {
    ASSERT_GE(rec->messages.size(), 2u) << s.proc.output() << sim.output();
    for (size_t k = 1; k < rec->messages.size(); ++k) {
      const loop_stats_t& m = rec->messages[k];
      SCOPED_TRACE(m.process);
      EXPECT_GT(m.cycles, 300);
      EXPECT_LE(m.period_error_p50_us, m.period_error_p99_us);
      EXPECT_LE(m.period_error_p99_us,
                std::max(m.period_max_us - 1000.0, 1000.0 - m.period_min_us) + 1e-9);
      // The controller manager's nominal period comes from the states: a loop woken by datagrams never keeps it to
      // the microsecond in 99 % of a window, so 0 would mean no errors were taken.
      if (m.process == "controller_manager") {
        EXPECT_GT(m.period_error_p99_us, 0.0);
      }
    }
  }
  EXPECT_EQ(s.proc.stop(5.0, SIGINT), 0);
  EXPECT_EQ(sim.stop(5.0, SIGINT), 0);
#endif
}
