// In-process test rig: a ControllerManager on an in-memory LCM (memq://) fed
// by simulated actuators (fake_hardware's dynamics) one cycle at a time, so
// unit tests drive the real loop deterministically without processes.
#pragma once

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "controller_manager/manager.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "test/controller_manager/alloc_counter.hpp"
#include "test/controller_manager/fake_hardware.hpp"
#include "test/support/process.hpp"
#include "controllers/builtin.hpp"

namespace lcm_control::testing {

inline std::string data(const std::string& file) { return source("test/controller_manager/data/" + file); }

struct Rig {
  explicit Rig(const cm::Registry& registry = cm::builtin_registry(), const std::string& urdf = data("test_bot.urdf"),
               const std::string& yaml = data("test_bot.yaml"), cm::ManagerOptions options = {})
      : model(load_robot_model(urdf, yaml)), bus("memq://", "") {
    act = actuators_for(model);
    cm = std::make_unique<cm::ControllerManager>(model, bus, registry, options);
  }

  // n control steps of `period_us` each.
  void cycle(int n = 1) {
    for (int k = 0; k < n; ++k) {
      fill_state(state, act, step, session, period_us, lockstep);
      state.utime += time_offset_us;
      cm->on_hardware_state(state);
      const hardware_command_t& c = cm->last_command();
      const bool answered = c.step == step && c.session == session && c.num_actuators == static_cast<int>(act.size());
      if (answered) commands.push_back(c);
      simulate(act, answered ? &c : nullptr, period_us * 1e-6);
      ++step;
      pump();
    }
  }
  // n cycles counting the heap allocations of the manager's handling of each state alone (alloc_counter.hpp): the
  // actuators move with the commands (`simulated`) or stand still, and what was published is sent between cycles
  // (`pumped`). Nothing is recorded in `commands`.
  long allocations_in_cycles(int n, bool simulated, bool pumped) {
    reset_allocations();
    for (int k = 0; k < n; ++k) {
      fill_state(state, act, step, session, period_us, lockstep);
      count_allocations(true);
      cm->on_hardware_state(state);
      count_allocations(false);
      if (simulated) simulate(act, &cm->last_command(), period_us * 1e-6);
      ++step;
      if (pumped) pump();
    }
    return allocations();
  }
  // Until quiet: what the controllers handed to the outbox is sent, and what that (or anything queued) makes them
  // publish too.
  void pump() {
    for (bool more = true; more;) {
      cm->flush_published();
      more = false;
      while (bus.lcm().handleTimeout(0) > 0) more = true;
    }
  }
  cm::Reply load(const std::string& name) { return cm->load(name); }
  // Switches and runs cycles until the reply comes (at once when no cycle ran yet).
  cm::Reply switch_(const std::vector<std::string>& start, const std::vector<std::string>& stop, int strictness = 2) {
    std::optional<cm::Reply> got;
    cm->switch_controllers(start, stop, strictness, [&](const cm::Reply& r) { got = r; });
    for (int k = 0; k < 5 && !got; ++k) cycle();
    return got.value_or(cm::Reply{false, "no reply"});
  }
  template <class Msg>
  void publish(const std::string& channel, const Msg& m) {
    bus.lcm().publish(channel, &m);
    pump();
  }
  FakeActuator& actuator(const std::string& name) { return find_actuator(act, name); }
  const cm::JointData& joint(const std::string& name) { return *cm->hardware().find(name); }

  RobotModel model;
  Bus bus;
  std::unique_ptr<cm::ControllerManager> cm;
  std::vector<FakeActuator> act;
  std::vector<hardware_command_t> commands;
  hardware_state_t state{};
  int64_t step = 0, session = 42, time_offset_us = 0;
  int period_us = 1000;
  bool lockstep = true;

  // Loads and starts `name` on a ticking loop (a controller started before the
  // first hardware state restarts, and forgets its command, when it arrives).
  void start(const std::string& name) {
    if (!cm->loop().has_state()) cycle();
    const cm::Reply l = load(name);
    ASSERT_TRUE(l.ok) << l.message;
    const cm::Reply s = switch_({name}, {});
    ASSERT_TRUE(s.ok) << s.message;
  }
};

// A trajectory goal: joints and (time_from_start, positions) points, no velocities.
inline joint_trajectory_t trajectory_goal(int64_t id, std::vector<std::string> joints,
                                          std::vector<std::pair<double, std::vector<double>>> pts) {
  joint_trajectory_t g{};
  g.goal_id = id;
  g.joint_names = joints;
  g.num_joints = static_cast<int32_t>(joints.size());
  for (auto& [t, pos] : pts) {
    trajectory_point_t p{};
    p.time_from_start = t;
    p.positions = pos;
    p.num_positions = static_cast<int32_t>(pos.size());
    g.points.push_back(p);
  }
  g.num_points = static_cast<int32_t>(g.points.size());
  return g;
}

}  // namespace lcm_control::testing
