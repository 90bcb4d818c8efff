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
