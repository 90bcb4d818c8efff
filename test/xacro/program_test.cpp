// The `xacro` program: output on stdout or -o, --deps, and its exit codes (0 done, 2 usage, 3 a bad input file).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "test/xacro/xacro_test_util.hpp"
#include "test/support/process.hpp"

namespace lcm_control::xacro {
namespace {

using lcm_control::testing::ChildProcess;

const std::string kXacro = LCM_CONTROL_BIN_DIR "/xacro";
const std::string kData = XACRO_TEST_DATA;

struct Result {
  int code;
  std::string output;
};

Result run(std::vector<std::string> args) {
  args.insert(args.begin(), kXacro);
  ChildProcess p(args);
  const int code = p.wait(30);
  return {code, p.output()};
}

TEST(XacroProgram, ExpandsToStdoutWithArgsAndPackagePath) {
  const Result r = run({kData + "/pkgs/demo_description/urdf/demo_arm.urdf.xacro", "--package-path", kData + "/pkgs",
                     "sim:=true", "prefix:=left_", "name:=twin", "frames:=3", "description_package:=", "--inorder"});
  EXPECT_EQ(r.code, 0) << r.output;
  std::ifstream in(kData + "/expected/demo_arm_sim.urdf");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string expected = ss.str();
  for (size_t p; (p = expected.find("@DATA_DIR@")) != std::string::npos;) expected.replace(p, 10, kData);
  EXPECT_EQ(r.output, expected);
}

TEST(XacroProgram, DepsListsTheFilesReadBesidesTheInput) {
  const Result r = run({kData + "/pkgs/demo_description/urdf/demo_arm.urdf.xacro", "--deps", "--package-path",
                     kData + "/pkgs"});
  EXPECT_EQ(r.code, 0) << r.output;
  const std::string u = kData + "/pkgs/demo_description/urdf/";
  EXPECT_EQ(r.output, u + "demo_arm_macro.xacro " + u + "inc/common.xacro " + u + "demo.ros2_control.xacro " + kData +
                          "/pkgs/demo_description/config/links.yaml " + kData +
                          "/pkgs/demo_description/config/limits.yaml " + u + "../config/limits.yaml");
}

TEST(XacroProgram, OutputFile) {
  testing::ScratchDir dir;
  const std::string main = dir.write("m.xacro", "<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\" name=\"r\">"
                                                "<xacro:arg name=\"w\" default=\"1\"/><a w=\"$(arg w)\"/></robot>");
  const Result r = run({main, "-o", dir.path("out/m.urdf"), "w:=2"});
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output, "");
  std::ifstream in(dir.path("out/m.urdf"));
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(testing::body(ss.str()), "<robot name=\"r\">\n  <a w=\"2\"/>\n</robot>\n");
}

TEST(XacroProgram, ExitCodes) {
  testing::ScratchDir dir;
  const std::string bad = dir.write("bad.xacro", "<robot>\n<a v=\"${nope}\"/>\n</robot>");
  Result r = run({bad});
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.output.find("xacro: error: " + bad + ":2: NameError: name 'nope' is not defined"), std::string::npos)
      << r.output;
  r = run({dir.path("missing.xacro")});
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.output.find("xacro: error: " + dir.path("missing.xacro") + ": xacro file not found (check the path)"),
            std::string::npos)
      << r.output;
  r = run({"--no-such-flag", bad});
  EXPECT_EQ(r.code, 2) << r.output;
  r = run({});
  EXPECT_EQ(r.code, 2) << r.output;
  r = run({bad, bad});
  EXPECT_EQ(r.code, 2) << r.output;
  r = run({"--help"});
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.output.find("Example: xacro"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace lcm_control::xacro
