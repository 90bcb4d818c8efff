// The loop itself: one-cycle switching, restarts, silence, statistics, and no
// allocation on the loop path.
#include "controller_manager/loop.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>

#include "controller_interface/registry.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "test/controller_manager/rig.hpp"
#include "controllers/builtin.hpp"

using namespace lcm_control;
using namespace lcm_control::cm;
using lcm_control::testing::data;
using lcm_control::testing::Rig;

namespace {
bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Writes `value` to its joint and logs the time of every update it makes.
std::map<std::string, std::vector<int64_t>> g_updates;
class RecorderController : public Controller {
 public:
  void init(ControllerContext& ctx) override {
    name_ = ctx.name();
    joint_ = ctx.claim(ctx.params().string("joint"), Interface::Position);
    value_ = ctx.params().number("value");
  }
  void starting(const Time&) override {}
  void update(const Time& now, double) override {
    joint_->command = value_;
    g_updates[name_].push_back(now.utime);
  }

 private:
  std::string name_;
  JointData* joint_ = nullptr;
  double value_ = 0;
};

// Busy-waits 200 µs per update, timing itself with its own clock: the independent measure of its execution time and
// period that the controller manager's statistics must agree with.
struct BusyTimes {
  std::vector<double> exec_us, start_us;
};
BusyTimes g_busy;
class BusyController : public Controller {
 public:
  void init(ControllerContext& ctx) override { joint_ = ctx.claim(ctx.params().string("joint"), Interface::Position); }
  void starting(const Time&) override {}
  void update(const Time&, double) override {
    using C = std::chrono::steady_clock;
    const auto t0 = C::now();
    while (C::now() - t0 < std::chrono::microseconds(200)) {
    }
    const auto t1 = C::now();
    g_busy.exec_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    g_busy.start_us.push_back(std::chrono::duration<double, std::micro>(t0.time_since_epoch()).count());
    joint_->command = 0;
  }

 private:
  JointData* joint_ = nullptr;
};

// Writes `value` to its joint and fails on its `fail_after`th update (ros2_control's return_type::ERROR).
class FailingController : public Controller {
 public:
  void init(ControllerContext& ctx) override {
    const std::string joint = ctx.params().string("joint");
    joint_ = ctx.claim(joint, Interface::Position);
    fail_after_ = int(ctx.params().number("fail_after"));
    if (ctx.params().boolean("chainable", false)) ctx.export_reference(joint, {Interface::Position}, joint_);
  }
  void starting(const Time&) override { updates_ = 0; }
  void update(const Time&, double) override {
    joint_->command = 1.0;
    if (++updates_ == fail_after_) fail("lost track of the target");
  }

 private:
  JointData* joint_ = nullptr;
  int fail_after_ = 0, updates_ = 0;
};

// Writes a command from its joint's state and its update count (what the loop's copy of the state and its own
// history give); with sleep_ms, sleeps that long per update. It counts its calls, the thread its updates ran on,
// and any call or command that came while an update ran (an is_async controller must never see one).
struct SleeperLog {
  std::atomic<int> updates{0}, starts{0}, stops{0}, overlaps{0};
  std::atomic<bool> in_update{false};
  std::atomic<double> got{0};
  std::thread::id thread;
  void reset() {
    updates = starts = stops = overlaps = 0;
    in_update = false;
    got = 0;
    thread = {};
  }
};
SleeperLog g_sleeper;
class SleeperController : public Controller {
 public:
  void init(ControllerContext& ctx) override {
    joint_ = ctx.claim(ctx.params().string("joint"), Interface::Position);
    sleep_ms_ = ctx.params().number("sleep_ms", 0);
    ctx.take_commands(false, 1, [](const double* v) {
      if (g_sleeper.in_update) ++g_sleeper.overlaps;
      g_sleeper.got = v[0];
    });
  }
  void starting(const Time&) override {
    if (g_sleeper.in_update) ++g_sleeper.overlaps;
    ++g_sleeper.starts;
    n_ = 0;
  }
  void update(const Time&, double period) override {
    g_sleeper.in_update = true;
    g_sleeper.thread = std::this_thread::get_id();
    if (sleep_ms_ > 0) std::this_thread::sleep_for(std::chrono::microseconds(int64_t(sleep_ms_ * 1000)));
    ++n_;
    joint_->command = 0.5 * joint_->position + 1e-3 * n_ + period;
    ++g_sleeper.updates;
    g_sleeper.in_update = false;
  }
  void stopping(const Time&) override {
    if (g_sleeper.in_update) ++g_sleeper.overlaps;
    ++g_sleeper.stops;
  }

 private:
  JointData* joint_ = nullptr;
  double sleep_ms_ = 0;
  int n_ = 0;
};

const Registry& test_registry() {
  static const Registry r = [] {
    Registry x;
    register_builtin(x);
    x.add("test/Recorder", [](const std::string&) { return std::make_unique<RecorderController>(); });
    x.add("test/Busy", [](const std::string&) { return std::make_unique<BusyController>(); });
    ControllerType failing;  // chainable: with `chainable: true` it exports its joint as a reference interface
    failing.info.name = "test/Failing";
    failing.info.chainable = true;
    failing.factory = [](const std::string&) { return std::make_unique<FailingController>(); };
    x.add(failing);
    x.add("test/Sleeper", [](const std::string&) { return std::make_unique<SleeperController>(); });
    return x;
  }();
  return r;
}
}  // namespace

TEST(ControllerManagerLoop, StopAStartBOnOneJointHappensInOneCycle) {
  g_updates.clear();
  Rig rig(test_registry(), data("test_bot.urdf"), data("switch_test.yaml"));
  ASSERT_TRUE(rig.load("rec_a").ok);
  ASSERT_TRUE(rig.load("rec_b").ok);
  ASSERT_TRUE(rig.switch_({"rec_a"}, {}).ok);
  rig.cycle(10);
  const Reply r = rig.switch_({"rec_b"}, {"rec_a"});
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(has(r.message, "switched in one cycle at step 10")) << r.message;
  rig.cycle(10);
  const auto& a = g_updates["rec_a"];
  const auto& b = g_updates["rec_b"];
  ASSERT_EQ(a.size(), 11u);  // steps 0..10: the switch comes after step 10's update
  ASSERT_EQ(b.size(), 10u);  // steps 11..20
  EXPECT_EQ(a.back(), 10000);
  EXPECT_EQ(b.front(), 11000);
  // Every cycle: exactly one of them commanded tilt, and the hardware got a position command.
  for (size_t k = 0; k < rig.commands.size(); ++k) {
    const auto& c = rig.commands[k];
    EXPECT_EQ(c.mode[0], hardware_command_t::MODE_POSITION) << "step " << c.step;
    EXPECT_EQ(c.command[0], c.step <= 10 ? 1.0 : 2.0) << "step " << c.step;
  }
}

TEST(ControllerManagerLoop, SwitchWithoutHardwareAppliesAtOnce) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  std::optional<Reply> got;
  rig.cm->switch_controllers({"slide_position"}, {}, 2, [&](const Reply& r) { got = r; });
  ASSERT_TRUE(got);
  EXPECT_TRUE(got->ok);
  EXPECT_TRUE(has(got->message, "switched at once (no hardware state received yet)")) << got->message;
}

TEST(ControllerManagerLoop, SilenceStopsUpdatesAndResumeRestartsFromTheCurrentState) {
  Rig rig;
  rig.lockstep = false;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);
  rig.cycle(5);
  EXPECT_TRUE(rig.cm->ticking());
  rig.cm->poll(monotonic_us() + 1000000);
  EXPECT_FALSE(rig.cm->ticking());
  // A switch while silent applies at once.
  ASSERT_TRUE(rig.load("tilt_position").ok);
  std::optional<Reply> got;
  rig.cm->switch_controllers({"tilt_position"}, {}, 2, [&](const Reply& r) { got = r; });
  ASSERT_TRUE(got);
  EXPECT_TRUE(has(got->message, "hardware is silent")) << got->message;
  // Somebody moved the joint meanwhile: on resume the controller holds where it is now.
  rig.actuator("slide_motor").position = 0.7;
  const int64_t restarts = rig.cm->loop().restarts();
  rig.cycle(2);
  EXPECT_EQ(rig.cm->loop().restarts(), restarts + 1);
  EXPECT_TRUE(rig.cm->ticking());
  EXPECT_DOUBLE_EQ(rig.commands.back().command[1], 0.7);
}

TEST(ControllerManagerLoop, NewSessionOrTimeGoingBackwardsRestartsControllers) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);
  rig.cycle(3);
  float64_t cmd{};
  cmd.data = 0.9;
  rig.publish("slide_position/command", cmd);
  rig.cycle(3);
  EXPECT_DOUBLE_EQ(rig.actuator("slide_motor").position, 0.9);
  rig.session = 43;  // the simulator restarted: the joint is back at 0.1
  rig.step = 0;
  rig.actuator("slide_motor").position = 0.1;
  rig.cycle(3);
  EXPECT_DOUBLE_EQ(rig.actuator("slide_motor").position, 0.1);
  rig.publish("slide_position/command", cmd);
  rig.cycle(2);
  rig.step = 1;  // same session, time going backwards
  rig.actuator("slide_motor").position = 0.2;
  rig.cycle(1);
  EXPECT_DOUBLE_EQ(rig.actuator("slide_motor").position, 0.2);
}

TEST(ControllerManagerLoop, RepeatedStepIsAnsweredWithoutUpdating) {
  Rig rig;
  ASSERT_TRUE(rig.load("arm_position").ok);
  ASSERT_TRUE(rig.switch_({"arm_position"}, {}).ok);
  rig.cycle(5);
  const auto before = rig.cm->loop().stats().cycles();
  fill_state(rig.state, rig.act, rig.step - 1, rig.session, 1000, true);
  rig.cm->on_hardware_state(rig.state);
  EXPECT_EQ(rig.cm->loop().stats().cycles(), before);
  EXPECT_EQ(rig.cm->last_command().step, rig.step - 1);
}

TEST(ControllerManagerLoop, ASwitchIsAppliedOnTheRepeatedStepOfAPausedHardware) {
  // A paused sim_server republishes its step: the spawner's switch must not wait for an update that never comes.
  Rig rig;
  ASSERT_TRUE(rig.load("arm_position").ok);
  rig.cycle(3);
  const int64_t paused_at = rig.step - 1;
  const auto before = rig.cm->loop().stats().cycles();
  std::optional<Reply> got;
  rig.cm->switch_controllers({"arm_position"}, {}, cm_request_t::STRICT, [&](const Reply& r) { got = r; });
  ASSERT_FALSE(got);
  fill_state(rig.state, rig.act, paused_at, rig.session, 1000, true);
  rig.cm->on_hardware_state(rig.state);
  ASSERT_TRUE(got);
  EXPECT_TRUE(got->ok) << got->message;
  EXPECT_TRUE(has(got->message, "at step " + std::to_string(paused_at))) << got->message;
  EXPECT_EQ(rig.cm->loop().stats().cycles(), before);  // no update
  const auto& c = rig.cm->last_command();
  EXPECT_EQ(c.step, paused_at);
  for (int a = 0; a < c.num_actuators; ++a)
    EXPECT_EQ(c.mode[a] != hardware_command_t::MODE_NONE, c.name[a] == "arm_motor") << c.name[a];  // now commanded
  // and the repeated step after that is plain again
  rig.cm->on_hardware_state(rig.state);
  EXPECT_EQ(rig.cm->loop().stats().cycles(), before);
}

// Lockstep's spawner races the paused sim's first state: started before the state came or on its republish, a
// controller answers the same steps with the same commands.
TEST(ControllerManagerLoop, AControllerStartedOnAPausedStepAnswersItAsIfStartedBeforeIt) {
  std::vector<int64_t> updates[2];
  std::vector<double> commands[2];
  for (int run = 0; run < 2; ++run) {
    g_updates.clear();
    Rig rig(test_registry(), data("test_bot.urdf"), data("switch_test.yaml"));
    ASSERT_TRUE(rig.load("rec_a").ok);
    if (run == 0) {
      ASSERT_TRUE(rig.switch_({"rec_a"}, {}).ok);  // no state yet: switched at once
    }
    rig.cycle(1);
    if (run == 1) {
      std::optional<Reply> got;
      rig.cm->switch_controllers({"rec_a"}, {}, cm_request_t::STRICT, [&](const Reply& r) { got = r; });
      fill_state(rig.state, rig.act, 0, rig.session, 1000, true);
      rig.cm->on_hardware_state(rig.state);  // step 0 again: the sim is paused
      ASSERT_TRUE(got && got->ok);
    }
    commands[run].push_back(rig.cm->last_command().command[0]);
    rig.cycle(2);
    for (size_t k = rig.commands.size() - 2; k < rig.commands.size(); ++k) commands[run].push_back(rig.commands[k].command[0]);
    updates[run] = g_updates["rec_a"];
  }
  EXPECT_EQ(updates[0], (std::vector<int64_t>{0, 1000, 2000}));
  EXPECT_EQ(updates[1], updates[0]);
  EXPECT_EQ(commands[0], (std::vector<double>{1.0, 1.0, 1.0}));
  EXPECT_EQ(commands[1], commands[0]);
}

TEST(ControllerManagerLoop, UnclaimedActuatorsGetModeNone) {
  Rig rig;
  ASSERT_TRUE(rig.load("wheel_velocity").ok);
  ASSERT_TRUE(rig.switch_({"wheel_velocity"}, {}).ok);
  rig.cycle(1);
  const auto& c = rig.commands.back();
  for (int a = 0; a < c.num_actuators; ++a)
    EXPECT_EQ(c.mode[a], c.name[a] == "wheel_motor" ? hardware_command_t::MODE_VELOCITY : hardware_command_t::MODE_NONE)
        << c.name[a];
}

TEST(ControllerManagerLoop, HardwareThatDoesNotMatchTheUrdfIsNotAnswered) {
  Rig rig;
  rig.actuator("arm_motor").mode = hardware_command_t::MODE_POSITION;
  rig.cycle(1);
  EXPECT_FALSE(rig.cm->loop().has_state());
}

TEST(ControllerManagerLoop, StatisticsCoverCyclesAndControllers) {
  Rig rig;
  ASSERT_TRUE(rig.load("joint_state_controller").ok);
  ASSERT_TRUE(rig.load("arm_position").ok);
  ASSERT_TRUE(rig.switch_({"joint_state_controller", "arm_position"}, {}).ok);
  rig.cycle(200);
  const auto s = rig.cm->statistics();
  EXPECT_GE(s.cycles, 199);
  EXPECT_GT(s.period_mean_us, 0);
  EXPECT_LE(s.period_min_us, s.period_max_us);
  EXPECT_GE(s.period_jitter_us, 0);
  EXPECT_EQ(s.item, (std::vector<std::string>{"joint_state_controller", "arm_position"}));
  EXPECT_GT(s.item_exec_mean_us[1], 0);
  EXPECT_EQ(s.unpublished, 0);  // joint_states went through the outbox, none dropped
  EXPECT_EQ(rig.cm->statistics().cycles, 0);
}

// ROS 2's controller statistics: a controller that busy-waits 200 µs per update is reported at what its own clock
// measured (execution time and period, mean within 10 %, p99 between mean and max), over one statistics window.
TEST(ControllerManagerLoop, StatisticsReportAControllersExecutionTimeAndPeriodAsItsOwnClockMeasuresThem) {
  const std::string dir = lcm_control::testing::temp_dir("busy_stats");
  const std::string yaml = dir + "/busy.yaml";
  std::ofstream(yaml) << "controller_manager:\n  ros__parameters:\n    update_rate: 1000\n"
                         "    busy: {type: test/Busy}\n    slow_busy: {type: test/Busy}\n"
                         "busy:\n  ros__parameters: {joint: tilt}\n"
                         "slow_busy:\n  ros__parameters: {joint: slide, update_rate: 250}\n";
  Rig rig(test_registry(), data("test_bot.urdf"), yaml);
  rig.start("busy");
  ASSERT_TRUE(rig.load("slow_busy").ok);
  rig.cm->statistics();  // a new window from here
  g_busy = {};
  rig.cycle(500);
  const size_t own_n = g_busy.exec_us.size();
  double own_exec = 0;
  for (double e : g_busy.exec_us) own_exec += e;
  own_exec /= double(own_n);
  const double own_period = (g_busy.start_us.back() - g_busy.start_us.front()) / double(own_n - 1);
  const auto s = rig.cm->statistics();
  ASSERT_EQ(s.item, (std::vector<std::string>{"busy", "slow_busy"}));
  EXPECT_EQ(s.item_kind[0], "controller");
  EXPECT_EQ(s.item_count[0], 500);
  EXPECT_GE(own_exec, 200.0) << "the busy-wait itself (longer when preempted: the statistics must follow it)";
  EXPECT_NEAR(s.item_exec_mean_us[0], own_exec, 0.1 * own_exec);
  EXPECT_GE(s.item_exec_p99_us[0], 0.98 * s.item_exec_mean_us[0]);
  EXPECT_LE(s.item_exec_p99_us[0], s.item_exec_max_us[0]);
  EXPECT_NEAR(s.item_period_mean_us[0], own_period, 0.1 * own_period);
  EXPECT_LE(s.item_period_p99_us[0], s.item_period_max_us[0]);
  EXPECT_EQ(s.item_count[1], 0) << "not running";
  std::printf("busy-wait 200 us: own clock exec %.1f us, period %.1f us; statistics exec mean %.1f p99 %.1f max %.1f, "
              "period mean %.1f p99 %.1f\n",
              own_exec, own_period, s.item_exec_mean_us[0], s.item_exec_p99_us[0], s.item_exec_max_us[0],
              s.item_period_mean_us[0], s.item_period_p99_us[0]);

  // At its own update_rate (every 4th cycle of 1 ms), its period is four cycles' time.
  ASSERT_TRUE(rig.switch_({"slow_busy"}, {}).ok);
  rig.cm->statistics();
  g_busy = {};
  rig.cycle(400);
  const auto t = rig.cm->statistics();
  EXPECT_EQ(t.item_count[1], 100);
  EXPECT_EQ(t.item_count[0], 400);
  EXPECT_NEAR(t.item_period_mean_us[1], 4 * t.item_period_mean_us[0], 0.1 * 4 * t.item_period_mean_us[0]);
}

// ROS 2's is_async in lockstep: the controller runs in the cycle it is due, so its commands are those of the same
// controller in the loop, to the bit, at every step (and at its own update_rate too).
TEST(ControllerManagerLoop, AnAsyncControllerInLockstepCommandsBitForBitAsInTheLoop) {
  const std::string dir = lcm_control::testing::temp_dir("async_lockstep");
  auto run = [&](bool async) {
    const std::string yaml = dir + (async ? "/async.yaml" : "/sync.yaml");
    std::ofstream(yaml) << "controller_manager:\n  ros__parameters:\n    update_rate: 1000\n"
                           "    tilt_ctl: {type: test/Sleeper}\n    slide_ctl: {type: test/Sleeper}\n"
                           "tilt_ctl:\n  ros__parameters: {joint: tilt, is_async: "
                        << (async ? "true" : "false")
                        << "}\nslide_ctl:\n  ros__parameters: {joint: slide, update_rate: 250, is_async: "
                        << (async ? "true" : "false") << "}\n";
    Rig rig(test_registry(), data("test_bot.urdf"), yaml);
    rig.start("tilt_ctl");
    rig.start("slide_ctl");
    EXPECT_EQ(rig.cm->loop().slots()[0]->async != nullptr, async);
    g_sleeper.reset();
    rig.cycle(400);
    EXPECT_EQ(g_sleeper.updates, 500) << "400 + 100 updates";
    EXPECT_EQ(g_sleeper.overlaps, 0);
    EXPECT_EQ(g_sleeper.thread, std::this_thread::get_id()) << "in lockstep the loop's thread runs it";
    std::vector<std::pair<double, double>> out;
    for (const auto& c : rig.commands) out.emplace_back(c.command[0], c.command[1]);
    return out;
  };
  const auto in_loop = run(false);
  const auto on_thread = run(true);
  ASSERT_GE(in_loop.size(), 400u);
  ASSERT_EQ(on_thread.size(), in_loop.size());
  for (size_t k = 0; k < in_loop.size(); ++k) ASSERT_EQ(on_thread[k], in_loop[k]) << "command " << k;
}

// ROS 2's is_async in real time: an update that sleeps 20 ms runs on the controller's own thread; every cycle is
// answered meanwhile (its joint keeps the last command), a due update is skipped while one runs, commands and
// switches that come meanwhile wait for it (never overlapping it), and a stop takes effect in its cycle.
TEST(ControllerManagerLoop, AnAsyncControllerRunsOnItsOwnThreadAndNeverHoldsTheLoop) {
  const std::string dir = lcm_control::testing::temp_dir("async_real_time");
  const std::string yaml = dir + "/async.yaml";
  std::ofstream(yaml) << "controller_manager:\n  ros__parameters:\n    update_rate: 1000\n"
                         "    sleeper: {type: test/Sleeper}\n    other: {type: test/Recorder}\n"
                         "sleeper:\n  ros__parameters: {joint: tilt, sleep_ms: 20, is_async: true}\n"
                         "other:\n  ros__parameters: {joint: tilt, value: 7}\n";
  Rig rig(test_registry(), data("test_bot.urdf"), yaml);
  rig.lockstep = false;
  g_sleeper.reset();
  rig.start("sleeper");
  ASSERT_TRUE(rig.load("other").ok);
  Endpoints& ends = *rig.cm->loop().slots()[0]->endpoints;
  AsyncUpdate& async = *rig.cm->loop().slots()[0]->async;
  rig.commands.clear();
  const int before = g_sleeper.updates;
  bool held = false, published = false;
  for (int k = 0; k < 100; ++k) {
    const bool was_busy = async.busy();
    rig.cycle();
    if (k >= 10 && !published && !was_busy && async.busy()) {  // an update of 20 ms began now: the command waits
      published = true;
      float64_t v{};
      v.data = 3.5;
      rig.publish("sleeper/command", v);
      held = ends.held() == 1 && g_sleeper.got == 0.0;
    }
    rig.cm->deliver_held();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_TRUE(held) << "a command that came while the update ran was held";
  EXPECT_EQ(g_sleeper.got, 3.5) << "and delivered after it";
  EXPECT_EQ(rig.commands.size(), 100u) << "every cycle answered";
  const int updates = g_sleeper.updates - before;
  EXPECT_GE(updates, 1);
  EXPECT_LE(updates, 9) << "at most one update per 20 ms in 100 cycles of >= 1 ms";
  EXPECT_GE(async.skipped(), 100 - 2 * updates);
  EXPECT_NE(g_sleeper.thread, std::this_thread::get_id());
  // The commands it wrote reached the hardware, each kept until the next one came.
  int changes = 0;
  for (size_t k = 1; k < rig.commands.size(); ++k)
    if (rig.commands[k].command[0] != rig.commands[k - 1].command[0]) ++changes;
  EXPECT_GE(changes, updates - 2);
  EXPECT_LE(changes, updates + 1);

  // A stop while an update runs: the switch is made in its cycle (another controller takes the joint at once), and
  // stopping() waits for the update to end.
  while (!async.busy()) rig.cycle();
  const Reply r = rig.switch_({"other"}, {"sleeper"});
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(has(r.message, "in one cycle")) << r.message;
  rig.cycle();
  EXPECT_EQ(rig.commands.back().command[0], 7.0) << "the other controller commands from the next cycle";
  EXPECT_EQ(g_sleeper.stops, 0) << "not while its update runs";
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  rig.cycle(3);
  EXPECT_EQ(g_sleeper.stops, 1);
  EXPECT_EQ(rig.commands.back().command[0], 7.0) << "its last update's command is not taken after it stopped";
  EXPECT_EQ(g_sleeper.overlaps, 0);
}

// ROS 2's fallback_controllers: a controller that fails in its update is stopped in that cycle and its fallbacks
// start in the same cycle, holding the joint and then commanding it; it cannot start while a fallback is not loaded;
// a fallback that is no controller of the file is refused at load, naming the key.
// A chain runs whole: the controller writing a failing controller's reference interface stops in the same cycle,
// and the log says so.
TEST(ControllerManagerLoop, AFailingChainMemberStopsTheControllersAboveIt) {
  const std::string dir = lcm_control::testing::temp_dir("chain_failure");
  const std::string yaml = dir + "/chain.yaml";
  std::ofstream(yaml) << "controller_manager:\n  ros__parameters:\n    update_rate: 1000\n"
                         "    tracker: {type: test/Failing}\n"
                         "    above: {type: passthrough_controller/PassthroughController}\n"
                         "tracker:\n  ros__parameters: {joint: tilt, fail_after: 5, chainable: true}\n"
                         "above:\n  ros__parameters: {interfaces: [tracker/tilt/position]}\n";
  Rig rig(test_registry(), data("test_bot.urdf"), yaml);
  rig.cycle();
  ASSERT_TRUE(rig.load("tracker").ok);
  const cm::Reply loaded = rig.load("above");
  ASSERT_TRUE(loaded.ok) << loaded.message;
  ASSERT_TRUE(rig.switch_({"tracker", "above"}, {}).ok);
  const cm::ControllerSlot* tracker = rig.cm->loop().slots()[0].get();
  const cm::ControllerSlot* above = rig.cm->loop().slots()[1].get();
  EXPECT_TRUE(tracker->controller->chained_mode());
  rig.cycle(10);
  EXPECT_FALSE(tracker->running);
  EXPECT_FALSE(above->running) << "it writes the failed controller's reference";
  EXPECT_EQ(above->chain_stopped_by, nullptr) << "reported and cleared by the manager";
}

TEST(ControllerManagerLoop, AFailingControllerIsStoppedAndItsFallbacksStartInThatCycle) {
  const std::string dir = lcm_control::testing::temp_dir("fallbacks");
  const std::string yaml = dir + "/fallbacks.yaml";
  std::ofstream(yaml) << "controller_manager:\n  ros__parameters:\n    update_rate: 1000\n"
                         "    tracker: {type: test/Failing}\n    safe: {type: test/Recorder}\n"
                         "    wrong: {type: test/Failing}\n"
                         "tracker:\n  ros__parameters: {joint: tilt, fail_after: 5, fallback_controllers: [safe]}\n"
                         "safe:\n  ros__parameters: {joint: tilt, value: 0.5}\n"
                         "wrong:\n  ros__parameters: {joint: tilt, fail_after: 5, fallback_controllers: [sfae]}\n";
  Rig rig(test_registry(), data("test_bot.urdf"), yaml);
  g_updates.clear();
  rig.cycle();
  ASSERT_TRUE(rig.load("tracker").ok);
  cm::Reply r = rig.switch_({"tracker"}, {});
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "cannot start 'tracker': its fallback controller 'safe' is not loaded")) << r.message;
  ASSERT_TRUE(rig.load("safe").ok);
  ASSERT_TRUE(rig.switch_({"tracker"}, {}).ok);
  const int64_t started = rig.commands.back().step;
  rig.cycle(10);
  const cm::ControllerSlot* tracker = rig.cm->loop().slots()[0].get();
  const cm::ControllerSlot* safe = rig.cm->loop().slots()[1].get();
  EXPECT_FALSE(tracker->running);
  EXPECT_TRUE(safe->running);
  EXPECT_EQ(tracker->failure, nullptr) << "reported and cleared by the manager";
  ASSERT_FALSE(g_updates["safe"].empty());
  // tracker's 5th update is at started + 5; safe (loaded after it) updates in that same cycle.
  EXPECT_EQ(g_updates["safe"].front(), (started + 5) * 1000);
  for (const auto& c : rig.commands) {
    if (c.step <= started || c.step > started + 5) continue;
    EXPECT_EQ(c.command[0], c.step < started + 5 ? 1.0 : 0.5) << "step " << c.step;
  }
  EXPECT_EQ(rig.commands.back().command[0], 0.5);

  r = rig.load("wrong");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "wrong/fallback_controllers")) << r.message;
  EXPECT_TRUE(has(r.message, "'sfae' is not a controller of " + yaml)) << r.message;
}

TEST(ControllerManagerLoop, ReloadRefusesWhileLoadedUnlessForced) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);
  rig.cycle(2);
  std::optional<Reply> got;
  rig.cm->reload(false, [&](const Reply& r) { got = r; });
  ASSERT_TRUE(got);
  EXPECT_FALSE(got->ok);
  EXPECT_TRUE(has(got->message, "1 controller(s) loaded (slide_position)")) << got->message;
  got.reset();
  rig.cm->reload(true, [&](const Reply& r) { got = r; });
  rig.cycle(1);
  ASSERT_TRUE(got);
  EXPECT_TRUE(got->ok) << got->message;
  EXPECT_TRUE(rig.cm->list().empty());
}

TEST(ControllerManagerLoop, NoAllocationOnTheLoopPath) {
  Rig rig;
  for (const char* n : {"joint_state_controller", "trajectory", "vel_group", "arm_position", "spin_velocity"})
    ASSERT_TRUE(rig.load(n).ok) << n;
  ASSERT_TRUE(
      rig.switch_({"joint_state_controller", "trajectory", "vel_group", "arm_position", "spin_velocity"}, {}).ok);
  rig.commands.reserve(10000);
  rig.cycle(50);
  rig.publish("trajectory/command", lcm_control::testing::trajectory_goal(
                                        1, {"slide", "tilt"}, {{0.1, {0.1, -0.1}}, {0.2, {0.2, -0.2}}, {0.3, {0.3, -0.3}}}));
  float64_array_t v{};
  v.size = 2;
  v.data = {1.0, 2.0};
  rig.publish("vel_group/command", v);
  rig.cycle(2);
  EXPECT_EQ(rig.allocations_in_cycles(500, false, false), 0);  // goal runs, finishes (result published), joint_states, PID states
}

TEST(ControllerManagerLoop, EStopReleaseRestartsControllers) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);
  rig.cycle(2);
  const int64_t restarts = rig.cm->loop().restarts();
  fill_state(rig.state, rig.act, rig.step++, rig.session, 1000, true);
  rig.state.e_stop = true;
  rig.cm->on_hardware_state(rig.state);
  rig.actuator("slide_motor").position = 0.4;  // moved by hand while stopped
  rig.cycle(1);                                // released
  EXPECT_EQ(rig.cm->loop().restarts(), restarts + 1);
  EXPECT_DOUBLE_EQ(rig.commands.back().command[1], 0.4);
}

TEST(ControllerManagerLoop, LockstepResumeWithTheNextStepContinuesWithoutRestart) {
  Rig rig;
  ASSERT_TRUE(rig.load("trajectory").ok);
  ASSERT_TRUE(rig.switch_({"trajectory"}, {}).ok);
  rig.cycle(5);
  rig.cm->poll(monotonic_us() + 1000000);  // a lost message: the hardware republishes later
  EXPECT_FALSE(rig.cm->ticking());
  const int64_t restarts = rig.cm->loop().restarts();
  rig.cycle(2);
  EXPECT_EQ(rig.cm->loop().restarts(), restarts);
  EXPECT_TRUE(rig.cm->ticking());
}

TEST(ControllerManagerLoop, ActuatorCountChangingWithinASessionIsReboundNotTrusted) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);
  rig.cycle(3);
  auto act = rig.act;
  act.pop_back();  // roll_motor disappears: the hardware no longer fits the URDF
  fill_state(rig.state, act, rig.step, rig.session, 1000, true);
  const int64_t cycles = rig.cm->loop().stats().cycles();
  rig.cm->on_hardware_state(rig.state);
  EXPECT_EQ(rig.cm->loop().stats().cycles(), cycles);  // not answered
  ++rig.step;
  rig.cycle(2);  // all six again: bound again, answered
  EXPECT_EQ(rig.cm->loop().stats().cycles(), cycles + 2);
}

// A controller manager (re)started under a robot that is not at 0: the cycle that starts a controller writes its
// joints before the controller's first update, and must command where the joint is, not 0 (issue 18).
TEST(ControllerManagerLoop, AStartedControllerHoldsTheMeasuredPositionUntilItsFirstUpdate) {
  g_updates.clear();
  Rig rig(test_registry(), data("test_bot.urdf"), data("switch_test.yaml"));
  rig.actuator("tilt_motor").position = 0.8;
  rig.cycle(3);
  ASSERT_TRUE(rig.load("rec_a").ok);
  const size_t before = rig.commands.size();
  ASSERT_TRUE(rig.switch_({"rec_a"}, {}).ok);
  rig.cycle(2);
  ASSERT_GE(rig.commands.size(), before + 3);
  const hardware_command_t& first = rig.commands[before];  // the switching cycle
  ASSERT_EQ(first.mode[0], hardware_command_t::MODE_POSITION);
  EXPECT_EQ(first.command[0], 0.8) << "step " << first.step;
  EXPECT_EQ(rig.commands[before + 1].command[0], 1.0);  // then the controller's own command
}

// A <ros2_control> joint handed from a velocity to a position controller in one switch: the switching cycle commands
// the measured position in position mode, not the velocity controller's last value read as a position.
TEST(ControllerManagerLoop, AHandOverThatChangesTheInterfaceHoldsTheMeasuredPosition) {
  Rig rig(cm::builtin_registry(), std::string(LCM_CONTROL_SOURCE_DIR) + "/test/robots/switch_arm.urdf",
          std::string(LCM_CONTROL_SOURCE_DIR) + "/test/robots/switch_arm.yaml");
  ASSERT_TRUE(rig.load("velocity_controller").ok);
  ASSERT_TRUE(rig.load("position_controller").ok);
  ASSERT_TRUE(rig.switch_({"velocity_controller"}, {}).ok);
  rig.cycle(3);
  ASSERT_EQ(rig.commands.back().mode[0], hardware_command_t::MODE_VELOCITY);
  rig.actuator("j1_actuator").position = 0.7;
  rig.cycle(1);
  const size_t before = rig.commands.size();
  const Reply r = rig.switch_({"position_controller"}, {"velocity_controller"});
  ASSERT_TRUE(r.ok) << r.message;
  ASSERT_GT(rig.commands.size(), before);
  const hardware_command_t& first = rig.commands[before];  // the switching cycle
  EXPECT_EQ(first.mode[0], hardware_command_t::MODE_POSITION);
  EXPECT_EQ(first.command[0], 0.7) << "step " << first.step;
}

// ROS 2's per-controller update_rate: a 100 Hz controller in a 1 kHz manager updates on exactly one cycle in ten,
// its period the ten cycles' time; one above the manager's rate is refused naming both rates.
TEST(ControllerManagerLoop, AControllersOwnUpdateRateUpdatesItOnEveryNthCycle) {
  const std::string dir = lcm_control::testing::temp_dir("own_rate");
  const std::string yaml = dir + "/rates.yaml";
  std::ofstream(yaml) << "controller_manager:\n  ros__parameters:\n    update_rate: 1000\n"
                         "    slow: {type: test/Recorder}\n    fast: {type: test/Recorder}\n"
                         "    too_fast: {type: test/Recorder}\n"
                         "slow:\n  ros__parameters: {joint: tilt, value: 0.1, update_rate: 100}\n"
                         "fast:\n  ros__parameters: {joint: slide, value: 0.2}\n"
                         "too_fast:\n  ros__parameters: {joint: slide, value: 0.2, update_rate: 2000}\n";
  Registry registry;
  registry.add("test/Recorder", [](const std::string&) { return std::make_unique<RecorderController>(); });
  Rig rig(registry, data("test_bot.urdf"), yaml);
  g_updates.clear();
  rig.start("slow");
  rig.start("fast");
  const size_t fast0 = g_updates["fast"].size(), slow0 = g_updates["slow"].size();
  rig.cycle(10000);
  EXPECT_EQ(g_updates["fast"].size() - fast0, 10000u);
  EXPECT_EQ(g_updates["slow"].size() - slow0, 1000u) << "one cycle in ten over 10,000 cycles";
  const auto& slow = g_updates["slow"];
  for (size_t k = slow0 + 1; k < slow.size(); ++k) ASSERT_EQ(slow[k] - slow[k - 1], 10000) << "every 10 ms";
  const cm::Reply r = rig.load("too_fast");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "too_fast/update_rate: 2000 Hz is above the controller manager's update_rate 1000 Hz"))
      << r.message;
}
