// Shared by the sim_server tests: test robots, model loading and a loop that
// drives an in-process Simulation with a command per step.
#pragma once

#include <functional>
#include <string>

#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "sim_server/simulation.hpp"

namespace lcm_control::sim::testing {

inline std::string data(const std::string& file) { return std::string(SIM_TEST_DATA) + "/" + file; }
inline std::string turret_urdf() { return std::string(LCM_CONTROL_SOURCE_DIR) + "/config/turret_bot.urdf"; }
inline std::string turret_yaml() { return std::string(LCM_CONTROL_SOURCE_DIR) + "/config/turret_bot.yaml"; }

inline RobotModel turret() { return load_robot_model(turret_urdf(), turret_yaml()); }
inline RobotModel modes_bot() { return load_robot_model(data("modes_bot.urdf"), data("modes_bot.yaml")); }
inline RobotModel pendulum() { return load_robot_model(data("pendulum.urdf"), data("pendulum.yaml")); }

constexpr int8_t kPos = hardware_command_t::MODE_POSITION;
constexpr int8_t kVel = hardware_command_t::MODE_VELOCITY;
constexpr int8_t kEff = hardware_command_t::MODE_EFFORT;
constexpr int8_t kNone = hardware_command_t::MODE_NONE;

// Runs `steps` control steps; before each, `each(step)` may set commands; after each, `check(step)`.
inline void run(Simulation& sim, int steps, const std::function<void(int)>& each,
                const std::function<void(int)>& check = {}) {
  for (int k = 0; k < steps; ++k) {
    if (each) each(k);
    sim.step();
    if (check) check(k);
  }
}

}  // namespace lcm_control::sim::testing
