// Loads a robot's URDF and ros_control YAML with lcm_control's robot model, loads
// one controller into an in-process controller manager, and encodes a message:
// what another project does with the installed headers and libraries.
#include <cstdio>

#include "bus/bus.hpp"
#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "controller_manager/manager.hpp"
#include "lcm_control/joint_state_t.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: consumer URDF YAML CONTROLLER\n");
    return 2;
  }
  const lcm_control::RobotModel model = lcm_control::load_robot_model(argv[1], argv[2], {});
  lcm_control::Bus bus("memq://", model.ns);
  lcm_control::cm::ControllerManager manager(model, bus);
  const lcm_control::cm::Reply loaded = manager.load(argv[3]);
  lcm_control::joint_state_t js{};
  std::printf("%zu joints, %zu controllers configured; %s; joint_state_t is %d bytes empty\n", model.joints.size(),
              model.controllers.size(), loaded.message.c_str(), js.getEncodedSize());
  return loaded.ok ? 0 : 1;
}
