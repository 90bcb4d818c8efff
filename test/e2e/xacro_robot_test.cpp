// A robot given as a .urdf.xacro (config/turret_bot_description: macros, a YAML of link dimensions, $(find), an
// argument for the hardware interface), taken as it is by doctor, sim_server, controller_manager and launch: the
// tutorial's demo from the xacro runs bit for bit as from config/turret_bot.urdf, its arguments reach every
// process, and a mistake in it stops the programs with the file, line and macro named. The real ROS 2 robots of
// ../shared/ros2_robots go to doctor, sim_server and launch as their xacros, with their arguments, when present.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
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

// Every xacro command of ../shared/ros2_robots (the official xacro's arguments, $(find) through the robot's pkgs/)
// given to doctor, sim_server (0.2 s of real time) and launch (--dry-run, the arguments as `xacro_args:`) as it is;
// the one whose block names Robotiq's real driver (its launch file's) is refused, naming the plugin.
TEST(XacroRobot, RealRos2RobotsGoToDoctorSimServerAndLaunchAsTheirXacros) {
  namespace fs = std::filesystem;
  const fs::path shared = lt::source("../shared/ros2_robots");
  if (!fs::exists(shared)) GTEST_SKIP() << "no " << shared.string() << " beside the checkout";
  int robots = 0, refused = 0;
  for (const auto& dir : fs::directory_iterator(shared)) {
    const fs::path commands = dir.path() / "expected/xacro_commands.json";
    if (!fs::exists(commands)) continue;
    std::vector<std::string> configs;
    for (const auto& y : fs::directory_iterator(dir.path() / "config"))
      if (y.path().extension() == ".yaml") configs.push_back(y.path().string());
    std::sort(configs.begin(), configs.end());
    ASSERT_FALSE(configs.empty()) << dir.path();
    const nlohmann::json list = nlohmann::json::parse(std::ifstream(commands));
    for (const auto& c : list["commands"]) {
      const std::string root = dir.path().string(), urdf = root + "/" + c["input"].get<std::string>();
      const std::string expected = c["expected"].get<std::string>();
      std::string config = configs.front();  // the one whose variant (position, velocity, ...) the file names
      for (const auto& y : configs) {
        const std::string stem = fs::path(y).stem().string(), variant = stem.substr(stem.rfind('_') + 1);
        if (expected.find(variant) != std::string::npos) config = y;
      }
      std::vector<std::string> xacro_args;
      std::string launch_args;
      for (const auto& a : c["args"]) {
        std::string arg = a.get<std::string>();
        for (size_t p; (p = arg.find("$R")) != std::string::npos;) arg.replace(p, 2, root);
        xacro_args.insert(xacro_args.end(), {"--xacro-arg", arg});
        const size_t eq = arg.find(":=");
        launch_args += "  " + arg.substr(0, eq) + ": '" + arg.substr(eq + 2) + "'\n";
      }
      SCOPED_TRACE(urdf + " (" + expected + ")");
      auto with = [&](std::vector<std::string> argv) {
        argv.insert(argv.end(), xacro_args.begin(), xacro_args.end());
        argv.insert(argv.end(), {"--package-path", root + "/pkgs"});  // $(find PKG) as the official run had it
        return argv;
      };
      // The description alone (the controllers' ROS 2 types and parameters are another matter).
      lt::ChildProcess doctor(with({lt::bin("doctor"), "--urdf", urdf}));
      const int doctor_exit = doctor.wait(30);
      const bool driver = doctor.output().find("is neither a simulator nor mock hardware") != std::string::npos;
      // doctor also checks the YAML the gz plugin names, as launch loads it (the chained demos' included).
      if (driver) {  // a real driver's block (Robotiq's launch file): refused, naming the plugin
        EXPECT_EQ(doctor_exit, 3) << doctor.output();
        ++refused;
      } else {
        EXPECT_EQ(doctor_exit, 0) << doctor.output();
        EXPECT_NE(doctor.output().find("ros2_control hardware"), std::string::npos) << doctor.output();
      }

      lt::ChildProcess sim(with({lt::bin("sim_server"), "--urdf", urdf, "--config", config, "--duration", "0.2",
                                 "--lcm-url", lt::unique_lcm_url()}));
      EXPECT_EQ(sim.wait(30), driver ? 3 : 0) << sim.output();

      const std::string file = lt::temp_dir("ros2_xacro_launch") + "/robot.launch.yaml";
      std::ofstream(file) << "urdf: " << urdf << "\nconfig: " << config << "\nxacro_args:\n" << launch_args;
      lt::ChildProcess launch({lt::bin("launch"), file, "--dry-run", "--package-path", root + "/pkgs"});
      if (driver) {  // launch reads the files first and names the plugin, as doctor and sim_server do
        EXPECT_EQ(launch.wait(30), 3) << launch.output();
        EXPECT_NE(launch.output().find("is neither a simulator nor mock hardware"), std::string::npos)
            << launch.output();
        ++robots;
        continue;
      }
      EXPECT_EQ(launch.wait(30), 0) << launch.output();
      EXPECT_NE(launch.output().find(fs::path(urdf).filename().string() + " --config"), std::string::npos)
          << launch.output();
      if (!xacro_args.empty()) {
        EXPECT_NE(launch.output().find("--xacro-arg " + xacro_args[1]), std::string::npos) << launch.output();
      }
      ++robots;
    }
  }
  EXPECT_EQ(robots, 20);  // the eleven packages of ../shared/ros2_robots, each expansion of theirs
  EXPECT_EQ(refused, 1);
}
