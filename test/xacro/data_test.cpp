// The project's own demo arm (data/): each command of data/expected/commands.json expands to its expected URDF,
// byte for byte, and reads the files --deps will list.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "xacro/xacro.hpp"
#include "test/xacro/xacro_test_util.hpp"

namespace lcm_control::xacro {
namespace {

const std::string kData = XACRO_TEST_DATA;

Options data_options() {
  Options o;
  o.find_package = [](const std::string& pkg) {
    const std::string dir = kData + "/pkgs/" + pkg;
    return std::filesystem::is_directory(dir) ? dir : std::string();
  };
  o.message = [](const std::string& line) { ADD_FAILURE() << "unexpected message: " << line; };
  return o;
}

TEST(XacroDemoArm, EveryCommandExpandsAsExpected) {
  std::ifstream in(kData + "/expected/commands.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j.at("commands").size(), 2u);
  for (const auto& c : j.at("commands")) {
    Options o = data_options();
    for (const auto& a : c.at("args")) o.args.push_back(parse_arg(a.get<std::string>()));
    const Expansion e = expand_file(kData + "/" + c.at("input").get<std::string>(), o);
    const std::string expected = testing::replace_all(testing::read(kData + "/" + c.at("expected").get<std::string>()), "@DATA_DIR@", kData);
    EXPECT_EQ(e.xml, expected) << c.at("expected");
  }
}

TEST(XacroDemoArm, FilesReadInReadOrderOnce) {
  const Expansion e = expand_file(kData + "/pkgs/demo_description/urdf/demo_arm.urdf.xacro", data_options());
  const std::string u = kData + "/pkgs/demo_description/urdf/";
  EXPECT_EQ(e.files_read, (std::vector<std::string>{
                              u + "demo_arm.urdf.xacro",
                              u + "demo_arm_macro.xacro",
                              u + "inc/common.xacro",
                              u + "demo.ros2_control.xacro",
                              kData + "/pkgs/demo_description/config/links.yaml",  // lazy_eval="false": first
                              kData + "/pkgs/demo_description/config/limits.yaml",
                              u + "../config/limits.yaml",
                          }));
}

}  // namespace
}  // namespace lcm_control::xacro
