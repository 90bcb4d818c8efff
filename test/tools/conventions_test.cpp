// One convention for every program (README "Flags and exit codes"): --help
// shows an example and exits 0, a usage error exits 2, a bad input file 3, no
// answer on the bus 4.
#include <gtest/gtest.h>

#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

using namespace lcm_control::testing;

namespace {

const std::vector<std::string> kPrograms = {
    "sim_server", "controller_manager", "launch",  "spawner",          "cmctl",           "turret-cmd",
    "send-trajectory", "state-logger", "state-publisher", "log2csv", "plotter", "tune", "doctor",
    "tracking-summary", "bus", "drive", "gripper"};

struct Outcome {
  int rc;
  std::string out;
};

Outcome run(std::vector<std::string> argv, const std::string& url = "") {
  argv[0] = bin(argv[0]);
  ChildProcess p(argv, url.empty() ? std::map<std::string, std::string>{}
                                   : std::map<std::string, std::string>{{"LCM_DEFAULT_URL", url}});
  const int rc = p.wait(15);
  return {rc, p.output()};
}

}  // namespace

TEST(Conventions, EveryProgramHelpsWithAnExampleAndExits2OnAUsageError) {
  for (const auto& program : kPrograms) {
    const Outcome help = run({program, "--help"});
    EXPECT_EQ(help.rc, 0) << program << "\n" << help.out;
    EXPECT_NE(help.out.find("Example"), std::string::npos) << program << " --help has no example\n" << help.out;
    const Outcome bad = run({program, "--no-such-flag"});
    EXPECT_EQ(bad.rc, 2) << program << "\n" << bad.out;
    EXPECT_NE(bad.out.find("Run with --help for more information"), std::string::npos) << program << "\n" << bad.out;
  }
}

TEST(Conventions, AMistypedSubcommandExits2NamingTheWordAndTheNearestOnes) {
  const Outcome cmctl = run({"cmctl", "lst"});
  EXPECT_EQ(cmctl.rc, 2) << cmctl.out;
  EXPECT_NE(cmctl.out.find("cmctl: error: 'lst' is not a command of cmctl; nearest: list; the commands: list, "
                           "list-types,"),
            std::string::npos)
      << cmctl.out;
  const Outcome bus = run({"bus", "--lcm-url", "udpm://239.255.76.67:7667?ttl=0", "plya", "run.lcmlog"});
  EXPECT_EQ(bus.rc, 2) << bus.out;
  EXPECT_NE(bus.out.find("bus: error: 'plya' is not a command of bus; nearest: play; the commands: list, hz, echo"),
            std::string::npos)
      << bus.out;
  EXPECT_NE(bus.out.find("Run with --help for more information"), std::string::npos) << bus.out;
  const Outcome alias = run({"cmctl", "list-controllers", "--no-such-flag"});  // a ROS 2 alias is a command
  EXPECT_EQ(alias.rc, 2) << alias.out;
  EXPECT_EQ(alias.out.find("is not a command"), std::string::npos) << alias.out;
  const Outcome none = run({"cmctl"});  // no word at all: CLI11's own message
  EXPECT_EQ(none.rc, 2) << none.out;
  EXPECT_NE(none.out.find("A subcommand is required"), std::string::npos) << none.out;
}

TEST(Conventions, ABadInputFileExits3NamingIt) {
  const std::string dir = temp_dir("conventions");
  const std::string missing = dir + "/missing";
  const std::vector<std::vector<std::string>> cases = {
      {"sim_server", "--urdf", missing + ".urdf"},
      {"controller_manager", "--urdf", missing + ".urdf", "--config", missing + ".yaml"},
      {"doctor", "--urdf", missing + ".urdf"},
      {"state-publisher", "--urdf", missing + ".urdf"},
      {"launch", missing + ".launch.yaml"},
      {"send-trajectory", "c", "--file", missing + ".yaml"},
      {"log2csv", missing + ".lcmlog"},
      {"plotter", "--log", missing + ".lcmlog", "joint_states/position[0]", "--output", dir + "/p.png"},
      {"tracking-summary", missing + ".lcmlog", "--joint", "j1=j1_controller/command"},
      {"bus", "info", missing + ".lcmlog"},
      {"log2csv", dir},  // a folder is not a log
  };
  for (const auto& argv : cases) {
    const Outcome r = run(argv);
    EXPECT_EQ(r.rc, 3) << argv[0] << "\n" << r.out;
    EXPECT_NE(r.out.find(argv[0] + ": error: " + dir), std::string::npos) << argv[0] << "\n" << r.out;
  }
}

TEST(Conventions, NoAnswerOnTheBusExits4NamingTheChannel) {
  const std::string url = unique_lcm_url();  // nothing runs here
  const std::string dir = temp_dir("conventions_bus");
  const std::vector<std::vector<std::string>> cases = {
      {"cmctl", "list", "--timeout", "0.5"},
      {"spawner", "j1_controller", "--timeout", "0.5"},
      {"tune", "j1", "--p", "1", "--timeout", "0.5"},
      {"send-trajectory", "c", "--point", "1:0", "--timeout", "0.5"},
      {"gripper", "c", "--position", "0.01", "--cm-timeout", "0.5"},
      {"turret-cmd", "j1_controller", "1", "--sim-time", "--timeout", "0.5"},
      {"state-logger", "joint_states", "--duration", "0.5", "--output", dir + "/js.csv"},
      {"plotter", "joint_states/position[0]", "--duration", "0.5", "--output", dir + "/p.png"},
      {"bus", "echo", "joint_states", "--duration", "0.5"},
  };
  for (const auto& argv : cases) {
    const Outcome r = run(argv, url);
    EXPECT_EQ(r.rc, 4) << argv[0] << "\n" << r.out;
    EXPECT_NE(r.out.find(argv[0] + ": error: "), std::string::npos) << argv[0] << "\n" << r.out;
    EXPECT_TRUE(r.out.find("joint_states") != std::string::npos || r.out.find("controller_manager/") != std::string::npos ||
                r.out.find("sim_server/gains") != std::string::npos)
        << argv[0] << " does not name a channel\n" << r.out;
  }
}
