// Controller libraries named in the YAML: what is refused before anything is registered, and why. (Loading a real
// library built outside the tree, and one built for another interface, is test/install/run.)
#include "controller_manager/plugins.hpp"

#include <dlfcn.h>
#include <gtest/gtest.h>
#include <lcm/lcm.h>

namespace lcm_control::cm {
namespace {

RobotModel with_plugin(const std::string& plugin) {
  RobotModel m;
  m.config_path = "/tmp/robot/config.yaml";
  ControllerSpec c;
  c.name = "mine";
  c.type = "my_controllers/Mine";
  c.params = YAML::Load("{type: my_controllers/Mine, plugin: " + plugin + "}");
  m.controllers.push_back(c);
  return m;
}

std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const ModelError& e) {
    return e.problems().front();
  }
  return "(not refused)";
}

TEST(Plugins, AMissingLibraryNamesTheYamlKeyAndWhereItLooked) {
  EXPECT_EQ(refusal([] { plugin_libraries(with_plugin("build/libmine.so")); }),
            "/tmp/robot/config.yaml: mine/plugin: /tmp/robot/build/libmine.so is not a file (build the library, or "
            "fix the path: it is relative to the YAML's folder)");
  EXPECT_NE(refusal([] { plugin_libraries(with_plugin("''")); }).find("mine/plugin: give the path of a controller "
                                                                      "library"),
            std::string::npos);
  EXPECT_TRUE(plugin_libraries(RobotModel{}).empty());
}

TEST(Plugins, ALibraryThatIsNotAControllerLibraryIsRefused) {
  Dl_info info{};
  ASSERT_NE(dladdr(reinterpret_cast<void*>(&lcm_create), &info), 0);  // liblcm: a shared library, not ours
  Registry r;
  const std::string why = refusal([&] { load_plugins(r, {info.dli_fname}); });
  EXPECT_NE(why.find(": not an lcm_control controller library (no lcm_control_plugin_abi / "
                     "lcm_control_register_controllers): export its types with LCM_CONTROL_CONTROLLER_PLUGIN"),
            std::string::npos)
      << why;
  EXPECT_TRUE(r.types().empty());
  EXPECT_NE(refusal([&] { load_plugins(r, {"/nonexistent/libx.so"}); })
                .find("/nonexistent/libx.so: cannot load the controller library: "),
            std::string::npos);
}

}  // namespace
}  // namespace lcm_control::cm
