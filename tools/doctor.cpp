// doctor: loads a URDF and a ros_control YAML the way sim_server and controller_manager will (or the robot a launch
// file starts), tries every configured controller exactly as controller_manager's load would (in-process, no bus),
// and prints what it resolved, or every problem. Exit 3 when the servers would refuse the files, a controller would be
// refused, or no controller is configured. The check: tools/lib/files/doctor.hpp.
#include "tools/lib/files/doctor.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  CLI::App app{
      "Check a URDF + ros_control YAML, or what a launch file starts, and print the robot model as the servers will "
      "use it; every configured controller is loaded in-process as controller_manager would load it.\n"
      "Examples:\n"
      "  doctor --urdf config/turret_bot.urdf --config config/turret_bot.yaml\n"
      "  doctor config/turret_bot.launch.yaml\n"
      "  doctor robot.launch use_sim:=true --package-path ~/catkin_ws/src",
      "doctor"};
  tools::DoctorFlags flags;
  tools::add_doctor_flags(app, flags);
  return run_program(app, argc, argv, [&] { return tools::run_doctor(flags); });
}
