// A robot given as a .urdf.xacro (config/turret_bot_description: macros, a YAML of link dimensions, $(find), an
// argument for the hardware interface), taken as it is by doctor, sim_server, controller_manager and launch: the
// tutorial's demo from the xacro runs bit for bit as from config/turret_bot.urdf, its arguments reach every
// process, and a mistake in it stops the programs with the file, line and macro named.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "lcm_control/joint_state_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lt = lcm_control::testing;
using lcm_control::joint_state_t;

namespace {

const std::string kXacro = lt::source("config/turret_bot_description/urdf/turret_bot.urdf.xacro");

// The tutorial's demo (config/turret_bot_demo.launch.yaml) for 3 s of sim time with `urdf`, as joint_states.
std::vector<joint_state_t> demo_run(const std::string& urdf, const std::string& extra_keys = "") {
  const std::string file = lt::temp_dir("xacro_demo") + "/demo.launch.yaml";
  std::ofstream(file) << "urdf: " << urdf << "\nconfig: " << lt::source("config/turret_bot.yaml")
                      << "\nmode: lockstep\ncontrollers: [joint_state_controller, j1_controller, j2_controller]\n"
                         "commands:\n  - {target: j1_controller, expr: [\"0.5\"], count: 1}\n"
                         "  - {target: j2_controller, expr: [\"3.14*sin(i/100)\"], rate: 60}\n"
                      << extra_keys;
  const std::string url = lt::unique_lcm_url();
  lcm::LCM lc(url);
  lt::Recorder<joint_state_t> states(lc, "joint_states");
  lt::ChildProcess launch({lt::bin("launch"), file, "--duration", "3", "--lcm-url", url});
  while (launch.running()) lc.handleTimeout(20);
  lt::pump_until(lc, [] { return false; }, 0.2);
  EXPECT_EQ(launch.wait(60), 0) << launch.output();
  return states.messages;
}

}  // namespace

TEST(XacroRobot, TheDemoFromTheXacroRunsBitForBitAsFromTheUrdf) {
  const auto from_urdf = demo_run(lt::source("config/turret_bot.urdf"));
  const auto from_xacro = demo_run(kXacro);
  ASSERT_GE(from_urdf.size(), 150u);
  ASSERT_EQ(from_urdf.size(), from_xacro.size());
  for (size_t k = 0; k < from_urdf.size(); ++k) {
    ASSERT_EQ(from_urdf[k].utime, from_xacro[k].utime) << k;
    ASSERT_EQ(from_urdf[k].position, from_xacro[k].position) << "t=" << from_urdf[k].utime * 1e-6;
  }
}

TEST(XacroRobot, ArgumentsReachDoctorAndEveryProcessLaunchStarts) {
  lt::ChildProcess doctor({lt::bin("doctor"), "--urdf", kXacro, "--config", lt::source("config/turret_bot.yaml"),
                           "--xacro-arg", "interface:=Velocity"});
  doctor.wait(30);
  EXPECT_NE(doctor.output().find("VelocityJointInterface"), std::string::npos) << doctor.output();

  const std::string file = lt::temp_dir("xacro_launch") + "/args.launch.yaml";
  std::ofstream(file) << "urdf: " << kXacro << "\nconfig: " << lt::source("config/turret_bot.yaml")
                      << "\nxacro_args: {interface: Effort}\ncontrollers: [joint_state_controller]\n";
  lt::ChildProcess dry({lt::bin("launch"), file, "--dry-run"});
  ASSERT_EQ(dry.wait(30), 0) << dry.output();
  size_t count = 0;
  for (size_t p = 0; (p = dry.output().find("--xacro-arg interface:=Effort", p)) != std::string::npos; ++p) ++count;
  EXPECT_EQ(count, 2u) << "sim_server and controller_manager each get the argument:\n" << dry.output();
}

TEST(XacroRobot, AMistakeStopsEveryProgramNamingTheFileLineAndMacro) {
  const std::string dir = lt::temp_dir("xacro_mistake");
  std::ofstream(dir + "/arm.urdf.xacro")
      << "<?xml version=\"1.0\"?>\n<robot name=\"arm\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
         "  <xacro:macro name=\"box_link\" params=\"name\">\n"
         "    <link name=\"${name}\"><inertial><mass value=\"${mass}\"/></inertial></link>\n"
         "  </xacro:macro>\n"
         "  <xacro:box_link name=\"base\"/>\n</robot>\n";
  for (const char* program : {"doctor", "sim_server", "controller_manager"}) {
    std::vector<std::string> argv{lt::bin(program), "--urdf", dir + "/arm.urdf.xacro", "--config",
                                  lt::source("config/turret_bot.yaml")};
    if (std::string(program) != "doctor") argv.insert(argv.end(), {"--lcm-url", lt::unique_lcm_url()});
    lt::ChildProcess p(argv);
    EXPECT_EQ(p.wait(30), 3) << program << ": " << p.output();
    EXPECT_NE(p.output().find("arm.urdf.xacro"), std::string::npos) << program << ": " << p.output();
    EXPECT_NE(p.output().find("mass"), std::string::npos) << program << ": " << p.output();
    EXPECT_NE(p.output().find("box_link"), std::string::npos) << program << ": " << p.output();
  }
}
