// roslaunch's substitution args as launch files and ros_control YAML use them: $(optenv) with a default of several
// words, $(eval) with nested parentheses and quotes, and errors that quote the whole substitution.
#include "description/substitution.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

#include "description/robot_model.hpp"
#include "test/support/process.hpp"

using namespace lcm_control;
namespace lt = lcm_control::testing;

namespace {
std::string error_of(const std::string& text, const Substitutions& subs) {
  try {
    substitute(text, subs, "f.launch:1");
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Substitution, OptenvTakesTheVariableElseItsDefaultOfSeveralWords) {
  unsetenv("LCM_CONTROL_TEST_OPTENV");
  EXPECT_EQ(substitute("x=$(optenv LCM_CONTROL_TEST_OPTENV a b c);", {}, "w"), "x=a b c;");
  setenv("LCM_CONTROL_TEST_OPTENV", "set", 1);
  EXPECT_EQ(substitute("x=$(optenv LCM_CONTROL_TEST_OPTENV a b c);", {}, "w"), "x=set;");
  unsetenv("LCM_CONTROL_TEST_OPTENV");
}

TEST(Substitution, EvalReadsArgsFindAndOptenvAsRoslaunchDoes) {
  Substitutions subs{{lt::source("test")}, {{"scale", "2"}, {"name", "arm"}}};
  EXPECT_EQ(substitute("$(eval max(1, min(scale * (3 + 1), 10)))", subs, "w"), "8");
  EXPECT_EQ(substitute("$(eval arg('name') + ')' + optenv('LCM_CONTROL_NO_SUCH_VAR', 'x'))", subs, "w"), "arm)x");
  EXPECT_EQ(substitute("$(eval find('robots') + '/gripper.urdf')", subs, "w"), lt::source("test/robots") + "/gripper.urdf");
}

TEST(Substitution, ErrorsQuoteTheWholeExpression) {
  const Substitutions subs{{}, {{"scale", "2"}}};
  const std::string e = error_of("$(eval min(scale * (3 + no_such_arg), 10))", subs);
  EXPECT_NE(e.find("f.launch:1: $(eval min(scale * (3 + no_such_arg), 10)): "), std::string::npos) << e;
  EXPECT_NE(e.find("no_such_arg"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  const std::string u = error_of("$(evil f(x) + 1)", subs);
  EXPECT_NE(u.find("'$(evil f(x) + 1)' is not supported"), std::string::npos) << u;
}

// One engine (xacro/substitution_args) reads both dialects: a YAML's $(...) has roslaunch's commands and ROS 2's
// $(var), not xacro's own $(dirname), $(anon) and $(cwd), and its refusals are worded for the YAML's user.
TEST(Substitution, TheYamlDialectIsTheXacroEnginesWithRoslaunchsCommands) {
  Substitutions subs{{lt::source("test")}, {{"prefix", "left_"}}};
  subs.missing_arg_fix = "give its value with --arg {0}=VALUE";
  EXPECT_EQ(substitute("$(var prefix)wheel $(arg prefix)arm", subs, "w"), "left_wheel left_arm");
  EXPECT_EQ(substitute("$(find robots)", subs, "w"), lt::source("test/robots"));
  for (const std::string xacro_only : {"$(dirname)", "$(anon node)", "$(cwd)"})
    EXPECT_EQ(error_of(xacro_only, subs),
              "f.launch:1: '" + xacro_only + "' is not supported (supported: $(find PKG), $(arg NAME), $(var NAME), "
                                             "$(env VAR), $(optenv VAR [default]), $(eval EXPR))");
  EXPECT_EQ(error_of("$(arg side)", subs), "f.launch:1: $(arg side) has no value; give its value with --arg side=VALUE");
  EXPECT_EQ(error_of("$(find no_such_package)", subs).rfind("f.launch:1: $(find no_such_package): package "
                                                             "'no_such_package' is not on the package path (",
                                                             0),
            0u);
  unsetenv("LCM_CONTROL_NO_SUCH_VAR");
  EXPECT_EQ(error_of("$(env LCM_CONTROL_NO_SUCH_VAR)", subs),
            "f.launch:1: $(env LCM_CONTROL_NO_SUCH_VAR): the environment variable is not set");
}
