// Hardware without physics, as ros2_control's mock_components/GenericSystem
// plays it: the state follows the command. A position command becomes the
// position (plus the block's position_state_following_offset); with
// calculate_dynamics the velocity is its finite difference, and a velocity
// command is integrated into the position (otherwise it only sets the
// velocity; calculate_dynamics defaults to true for ros2_control_demos'
// hardware, which integrates); an effort command becomes the effort. Mimic joints follow their
// joint (multiplier x position + offset, multiplier x velocity). Nobody
// commanding, the watchdog or the e-stop hold the position with velocity and
// effort 0. Pure: no Bullet, no LCM, no allocation after construction.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "description/robot_model.hpp"
#include "sim_server/played_hardware.hpp"

namespace lcm_control::sim {

// True when the robot has <ros2_control> blocks and every one names mock hardware (mock_components/GenericSystem,
// fake_components/GenericSystem): sim_server then plays it without physics.
bool all_mock_hardware(const RobotModel& model);

class MockHardware final : public PlayedHardware {
 public:
  // Starts at `initial` (joint -> position; others at 0, clamped into their limits, one line each in
  // start_warnings()). Throws ModelError for an initial position naming no moving joint or not finite, or a
  // hardware <param> that is not a number / bool.
  MockHardware(const RobotModel& model, const InitialPositions& initial);

  // One control period of `dt` seconds: the newest commands become the state.
  void step(double dt);

  int size() const override { return int(actuators_.size()); }
  const std::string& name(int i) const override { return actuators_[i].name; }
  const std::string& joint(int i) const override { return joints_[actuators_[i].joint].name; }
  int8_t wire_mode(int i) const override { return actuators_[i].wire_mode; }
  bool offers(int i, int8_t wire_mode) const override;
  const char* mode_name(int i) const override;
  bool set_command(int i, int8_t wire_mode, double value, double damping = 0) override;  // damping: not used
  void set_hold_all(bool hold) override { hold_all_ = hold; }
  bool hold_all() const override { return hold_all_; }
  void set_e_stop(bool engaged) override { e_stop_ = engaged; }
  bool e_stop() const override { return e_stop_; }
  bool has_pid(int) const override { return false; }
  const PidGains& gains(int) const override { return no_gains_; }
  bool set_gains(int, const PidGains&) override { return false; }
  double position(int i) const override;
  double velocity(int i) const override;
  double effort(int i) const override;

  // Every moving joint of the URDF (mimic joints too), in joint units; NaN for a joint it does not know.
  double joint_position(const std::string& joint) const;
  double joint_velocity(const std::string& joint) const;
  const std::vector<std::string>& start_warnings() const { return start_warnings_; }
  // One line per actuator for the INFO log: offered modes and the mock's parameters.
  std::string describe(int i) const;

 private:
  static constexpr int kWireModes = 4;  // MODE_NONE .. MODE_EFFORT

  struct JointState {
    std::string name;
    double q = 0, qd = 0, effort = 0;
  };
  struct Actuator {
    std::string name;
    int joint = -1;  // in joints_
    SimpleTransmission map;
    bool offered[kWireModes] = {};
    int8_t wire_mode = 0;
    bool commanded = false;
    double command = 0;  // joint units
    bool calculate_dynamics = false;
    double following_offset = 0;  // position_state_following_offset
  };
  struct MimicLink {
    int joint = -1, leader = -1;
    double multiplier = 1, offset = 0;
  };

  int joint_index(const std::string& name) const;

  std::vector<JointState> joints_;
  std::vector<Actuator> actuators_;
  std::vector<MimicLink> mimics_;
  std::vector<std::string> start_warnings_;
  bool hold_all_ = false, e_stop_ = false;
  PidGains no_gains_;
};

}  // namespace lcm_control::sim
