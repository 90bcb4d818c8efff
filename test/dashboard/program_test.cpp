// The dashboard program itself: what it serves of a robot's files, and what it says when it cannot start.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "test/dashboard/http_get.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lcm_control::dashboard {
namespace {

namespace fs = std::filesystem;
using testing::bin;
using testing::ChildProcess;
using testing::source;

int port_of(const std::string& output) {
  std::smatch m;
  return std::regex_search(output, m, std::regex(R"(http://127\.0\.0\.1:(\d+)/)")) ? std::stoi(m[1]) : -1;
}

TEST(DashboardProgram, ServesTheUrdfItsMeshesAndPackagesButNothingOutside) {
  const fs::path dir = testing::temp_dir("dashboard_program");
  fs::create_directories(dir / "pkgs" / "my_robot" / "meshes");
  fs::copy_file(source("test/sim_server/data/cube.stl"), dir / "pkgs" / "my_robot" / "meshes" / "cube.stl");
  std::ofstream(dir / "pkgs" / "secret.txt") << "not for browsers";
  ChildProcess dash({bin("dashboard"), "--urdf", source("test/sim_server/data/modes_bot.urdf"), "--port", "0",
                     "--package-path", (dir / "pkgs").string(), "--lcm-url", testing::unique_lcm_url(),
                     "--duration", "20"});
  ASSERT_TRUE(dash.wait_for_output("dashboard: http", 10)) << dash.output();
  const int port = port_of(dash.output());
  ASSERT_GT(port, 0) << dash.output();
  EXPECT_EQ(http_get(port, "/").status, 200);
  EXPECT_NE(http_get(port, "/").body.find("dashboard.js"), std::string::npos);
  EXPECT_EQ(http_get(port, "/robot/modes_bot.urdf").status, 200);
  EXPECT_EQ(http_get(port, "/robot/cube.stl").status, 200);  // a mesh beside the URDF (a relative filename)
  EXPECT_EQ(http_get(port, "/package/my_robot/meshes/cube.stl").status, 200);
  // file:// URIs (xacro's force_abs_paths) as /file/<absolute path>: inside a package or the URDF's folder only.
  const std::string pkgs = fs::canonical(dir / "pkgs").string();
  EXPECT_EQ(http_get(port, "/file" + pkgs + "/my_robot/meshes/cube.stl").status, 200);
  EXPECT_EQ(http_get(port, "/file" + fs::canonical(source("test/sim_server/data/cube.stl")).string()).status, 200);
  for (const std::string& outside : std::vector<std::string>{"/file/etc/passwd", "/file" + pkgs + "/secret.txt",
                                    "/file" + pkgs + "/my_robot/../secret.txt", "/file" + pkgs + "/my_robot/%2e%2e/secret.txt",
                                    "/file" + pkgs + "/my_robot", "/file/"})
    EXPECT_EQ(http_get(port, outside).status, 404) << outside;
  for (const char* outside : {"/robot/../pendulum.yaml", "/robot/%2e%2e/pendulum.yaml",
                              "/package/my_robot/../secret.txt", "/package/my_robot/%2e%2e/secret.txt",
                              "/package/no_such_pkg/meshes/cube.stl", "/package/my_robot", "/robot/"})
    EXPECT_EQ(http_get(port, outside).status, 404) << outside;
  // Another site's page, and a name that is not this computer's (DNS rebinding), are refused.
  EXPECT_EQ(http_get(port, "/ws", "Origin: https://evil.example\r\nUpgrade: websocket\r\n").status, 403);
  EXPECT_EQ(http_get(port, "/robot/modes_bot.urdf", "Host: evil.example\r\n").status, 403);
  dash.stop();
}

// A .urdf.xacro is expanded once (with --xacro-arg) and served under the URDF's name; its meshes are found as a
// URDF's are.
TEST(DashboardProgram, ServesAXacroAsTheUrdfItExpandsTo) {
  ChildProcess dash({bin("dashboard"), "--urdf", source("config/turret_bot_description/urdf/turret_bot.urdf.xacro"),
                     "--xacro-arg", "interface:=Effort", "--port", "0", "--lcm-url", testing::unique_lcm_url(),
                     "--duration", "20"});
  ASSERT_TRUE(dash.wait_for_output("dashboard: http", 10)) << dash.output();
  const int port = port_of(dash.output());
  ASSERT_GT(port, 0) << dash.output();
  const auto urdf = http_get(port, "/robot/turret_bot.urdf");
  EXPECT_EQ(urdf.status, 200);
  EXPECT_NE(urdf.body.find("hardware_interface/EffortJointInterface"), std::string::npos) << urdf.body;
  EXPECT_EQ(urdf.body.find("xacro:"), std::string::npos) << urdf.body;
  EXPECT_EQ(http_get(port, "/robot/turret_bot_macros.xacro").status, 200);  // the folder's files, as for a URDF
  dash.stop();
}

TEST(DashboardProgram, SaysWhatToDoWhenItCannotStart) {
  ChildProcess first({bin("dashboard"), "--port", "0", "--lcm-url", testing::unique_lcm_url(), "--duration", "20"});
  ASSERT_TRUE(first.wait_for_output("dashboard: http", 10)) << first.output();
  const int port = port_of(first.output());
  ChildProcess second({bin("dashboard"), "--port", std::to_string(port), "--lcm-url", testing::unique_lcm_url()});
  EXPECT_EQ(second.wait(10), 1);
  EXPECT_NE(second.output().find("--port"), std::string::npos) << second.output();

  ChildProcess no_page({bin("dashboard"), "--web-root", "/nonexistent", "--lcm-url", testing::unique_lcm_url()});
  EXPECT_EQ(no_page.wait(10), 1);
  EXPECT_NE(no_page.output().find("dashboard_page"), std::string::npos) << no_page.output();

  ChildProcess no_urdf({bin("dashboard"), "--urdf", "/nonexistent.urdf", "--lcm-url", testing::unique_lcm_url()});
  EXPECT_EQ(no_urdf.wait(10), 1);
  EXPECT_NE(no_urdf.output().find("/nonexistent.urdf"), std::string::npos) << no_urdf.output();

  ChildProcess open({bin("dashboard"), "--port", "0", "--bind", "0.0.0.0", "--read-only", "--lcm-url",
                     testing::unique_lcm_url(), "--duration", "1"});
  EXPECT_EQ(open.wait(10), 0);
  EXPECT_NE(open.output().find("no authentication"), std::string::npos) << open.output();
  first.stop();
}

}  // namespace
}  // namespace lcm_control::dashboard
