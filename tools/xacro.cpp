// xacro: expands a .xacro robot description (macros, properties, includes, ${...}, $(arg/find/env ...),
// xacro.load_yaml) into the document the official ROS xacro prints, without ROS: $(find PKG) is searched on
// --package-path, $LCM_CONTROL_PACKAGE_PATH and $ROS_PACKAGE_PATH, then beside the file's own package. Exit 0 done, 2 bad command line, 3 a file that
// cannot be expanded (the message names the file:line and the macro calls and includes that led there).
#include "tools/lib/files/xacro_program.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Expand a xacro file (a robot's .urdf.xacro) into its URDF, as the official ROS xacro does, without ROS.\n"
      "Example: xacro ur_gz.urdf.xacro ur_type:=ur5e name:=ur --package-path ~/robots -o ur5e.urdf",
      "xacro"};
  XacroFlags flags;
  add_xacro_flags(app, flags);
  return run_program(app, argc, argv, [&] { return run_xacro(flags); });
}
