// A stand-in for sim_server in tests: speaks docs/hardware-protocol.md
// (hardware/state out, hardware/command in, actuator space) on its own thread
// and LCM instance, in lockstep (default) or paced at the wall clock, with
// simple dynamics: position actuators go where commanded, velocity actuators
// integrate, effort actuators are a double integrator with optional gravity
// (I*a = u - gravity*sin(q) - damping*v).
#pragma once

#include <atomic>
#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "description/robot_model.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"

namespace lcm_control::testing {

struct FakeActuator {
  std::string name;
  int8_t mode = hardware_command_t::MODE_POSITION;
  double position = 0, velocity = 0, effort = 0;
  double inertia = 1.0, gravity = 0.0, damping = 0.0;
};

// One actuator per transmission of `model`, mode from its interface.
std::vector<FakeActuator> actuators_for(const RobotModel& model);
FakeActuator& find_actuator(std::vector<FakeActuator>& actuators, const std::string& name);

// One step of the dynamics under `command` (nullptr: nobody commands); returns
// how many actuator commands were dropped for a wrong mode.
int simulate(std::vector<FakeActuator>& actuators, const hardware_command_t* command, double dt);
void fill_state(hardware_state_t& state, const std::vector<FakeActuator>& actuators, int64_t step, int64_t session,
                int period_us, bool lockstep);

struct FakeHardwareOptions {
  bool lockstep = true;
  int period_us = 1000;
  double republish_s = 0.05;  // lockstep: republish the state while nobody answers
  std::string ns;             // channel prefix
};

class FakeHardware {
 public:
  struct Record {
    int64_t step;
    std::vector<int8_t> mode;
    std::vector<double> command;
    std::vector<double> position;  // after the step
  };

  FakeHardware(const std::string& url, std::vector<FakeActuator> actuators, FakeHardwareOptions options = {});
  ~FakeHardware();  // stops the thread

  void start();
  void stop();
  void pause(bool paused);  // stop publishing and stepping
  // A new session starting at step 0 and time 0 (a restarted simulator).
  void restart_session();

  int64_t step();
  std::vector<FakeActuator> actuators();
  FakeActuator actuator(const std::string& name);
  void set_position(const std::string& name, double position);
  std::vector<Record> records();  // every command applied, in order
  int64_t dropped();              // commands with a wrong mode or session
  // Waits until `n` more steps have been taken; false on timeout.
  bool run_steps(int64_t n, double timeout_s);

 private:
  void run();
  void on_command(const lcm::ReceiveBuffer*, const std::string&, const hardware_command_t* m);
  void publish_state();
  void record(const hardware_command_t* command);  // with mutex_ held

  lcm::LCM lcm_;
  FakeHardwareOptions options_;
  std::mutex mutex_;
  std::vector<FakeActuator> act_;
  std::vector<Record> records_;
  int64_t step_ = 0, session_ = 0, dropped_ = 0;
  bool have_command_ = false;
  hardware_command_t last_;
  std::atomic<bool> running_{false}, paused_{false}, restart_{false};
  std::thread thread_;
};

}  // namespace lcm_control::testing
