// Mesh paths: package://NAME/... on the package path, relative to the URDF's folder, file://.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "description/robot_model.hpp"
#include "description/packages.hpp"
#include "description/urdf_reader.hpp"
#include "test/support/process.hpp"

using namespace lcm_control;
namespace fs = std::filesystem;

class Resources : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = lcm_control::testing::temp_dir("resources");
    fs::create_directories(root_ + "/ws/src/my_robot/meshes");
    fs::create_directories(root_ + "/urdf/meshes");
    std::ofstream(root_ + "/ws/src/my_robot/meshes/arm.stl") << "solid x\nendsolid x\n";
    std::ofstream(root_ + "/urdf/meshes/local.stl") << "solid x\nendsolid x\n";
  }
  std::string root_;
};

TEST_F(Resources, PackageUriOnThePath) {
  const std::string want = fs::canonical(root_ + "/ws/src/my_robot/meshes/arm.stl").string();
  EXPECT_EQ(resolve_resource("package://my_robot/meshes/arm.stl", "/", {root_ + "/ws/src"}), want);
  EXPECT_EQ(resolve_resource("package://my_robot/meshes/arm.stl", "/", {root_ + "/ws/src/my_robot"}), want);
  EXPECT_EQ(resolve_resource("package://my_robot/meshes/arm.stl", "/", {root_ + "/ws"}), want);  // one level down
  EXPECT_EQ(resolve_resource("package://my_robot/meshes/arm.stl", "/", {"/nonexistent", root_ + "/ws/src"}), want);
  EXPECT_EQ(resolve_resource("package://other/meshes/arm.stl", "/", {root_ + "/ws/src"}), "");
  EXPECT_EQ(resolve_resource("package://my_robot/meshes/nope.stl", "/", {root_ + "/ws/src"}), "");
}

TEST_F(Resources, RelativeAbsoluteAndFileUri) {
  const std::string want = fs::canonical(root_ + "/urdf/meshes/local.stl").string();
  EXPECT_EQ(resolve_resource("meshes/local.stl", root_ + "/urdf", {}), want);
  EXPECT_EQ(resolve_resource(want, "/elsewhere", {}), want);
  EXPECT_EQ(resolve_resource("file://" + want, "/elsewhere", {}), want);
  EXPECT_EQ(resolve_resource("meshes/local.stl", root_, {}), "");
}

TEST_F(Resources, EnvironmentPackagePath) {
  setenv("LCM_CONTROL_PACKAGE_PATH", (root_ + "/nothing:" + root_ + "/ws/src").c_str(), 1);
  const auto path = default_package_path();
  unsetenv("LCM_CONTROL_PACKAGE_PATH");
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(path[1], root_ + "/ws/src");
  EXPECT_EQ(find_package_dir("my_robot", path), root_ + "/ws/src/my_robot");
}

TEST_F(Resources, APackageOffThePathIsOneErrorForAllItsMeshes) {
  const std::string urdf = root_ + "/urdf/arm.urdf";
  std::string links;
  for (const char* l : {"base", "shoulder", "upper_arm", "forearm"})
    links += fmt::format(R"(<link name="{0}"><collision><geometry><mesh filename="package://arm_description/meshes/{0}.stl"/></geometry></collision>
    <visual><geometry><mesh filename="package://arm_description/meshes/{0}.dae"/></geometry></visual></link>
)", l);
  std::ofstream(urdf) << "<robot name=\"arm\">" << links << R"(
  <joint name="j1" type="continuous"><parent link="base"/><child link="shoulder"/></joint>
  <joint name="j2" type="continuous"><parent link="shoulder"/><child link="upper_arm"/></joint>
  <joint name="j3" type="continuous"><parent link="upper_arm"/><child link="forearm"/></joint>
</robot>)";
  try {
    RobotModel m;
    LoadOptions o;
    o.package_path = {root_ + "/ws/src"};
    load_urdf_into(m, urdf, o);
    FAIL() << "missing package accepted";
  } catch (const ModelError& e) {
    ASSERT_EQ(e.problems().size(), 1u) << e.what();
    EXPECT_EQ(e.problems()[0],
              urdf + ": package 'arm_description' of 4 collision meshes not found (first: link 'base' "
                     "(package://arm_description/meshes/base.stl)); give --package-path DIR with DIR the folder "
                     "holding arm_description/ (or set LCM_CONTROL_PACKAGE_PATH or ROS_PACKAGE_PATH); searched: " +
                     root_ + "/ws/src");
  }
}

TEST_F(Resources, UrdfMeshesResolvedAtLoadAndMissingCollisionMeshNamed) {
  const std::string urdf = root_ + "/urdf/r.urdf";
  std::ofstream(urdf) << R"(<robot name="r">
  <link name="a"><collision><geometry><mesh filename="package://my_robot/meshes/arm.stl" scale="2 2 2"/></geometry></collision>
    <visual><geometry><mesh filename="meshes/local.stl"/></geometry></visual></link>
  <link name="b"><collision><geometry><mesh filename="meshes/missing.stl"/></geometry></collision></link>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint>
</robot>)";
  try {
    RobotModel m;
    LoadOptions o;
    o.package_path = {root_ + "/ws/src"};
    load_urdf_into(m, urdf, o);
    FAIL() << "missing collision mesh accepted";
  } catch (const ModelError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("link 'b' (meshes/missing.stl): collision mesh not found"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("link 'a'"), std::string::npos) << msg;
  }
  std::string text;
  {
    std::ifstream in(urdf);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  text.replace(text.find("meshes/missing.stl"), 18, "meshes/local.stl");
  std::ofstream(urdf) << text;
  RobotModel m;
  LoadOptions o;
  o.package_path = {root_ + "/ws/src"};
  load_urdf_into(m, urdf, o);
  EXPECT_EQ(m.links[0].collisions[0].mesh_path, fs::canonical(root_ + "/ws/src/my_robot/meshes/arm.stl").string());
  EXPECT_TRUE(m.links[0].collisions[0].scale.isApprox(Eigen::Vector3d(2, 2, 2)));
  EXPECT_EQ(m.links[0].visuals[0].mesh_path, fs::canonical(root_ + "/urdf/meshes/local.stl").string());
}
