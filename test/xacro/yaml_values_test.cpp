// xacro.load_yaml's typing: PyYAML safe_load's YAML 1.1 scalars and xacro's !degrees / !radians unit tags.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "xacro/process_error.hpp"
#include "xacro/yaml_values.hpp"

namespace lcm_control::xacro {
namespace {

Value scalar(const std::string& text) {
  const Value v = load_yaml_text("v: " + text + "\n");
  return *v.as_dict().find(Value::string("v"));
}

TEST(XacroYamlValues, ScalarsTypedAsPyYaml) {
  EXPECT_EQ(scalar("1e-3").kind(), Value::Kind::Str);  // YAML 1.1: no dot, no float
  EXPECT_EQ(scalar("1.0e3").kind(), Value::Kind::Str);  // YAML 1.1: the exponent needs its sign
  EXPECT_DOUBLE_EQ(scalar("1.0e-3").as_double(), 0.001);
  EXPECT_EQ(scalar("12").as_int(), 12);
  EXPECT_EQ(scalar("-7").as_int(), -7);
  EXPECT_EQ(scalar("0x1F").as_int(), 31);
  EXPECT_EQ(scalar("010").as_int(), 8);
  EXPECT_EQ(scalar("1_000").as_int(), 1000);
  EXPECT_DOUBLE_EQ(scalar(".5").as_double(), 0.5);
  EXPECT_DOUBLE_EQ(scalar("-2.").as_double(), -2.0);
  EXPECT_TRUE(std::isinf(scalar(".inf").as_double()));
  EXPECT_EQ(scalar("yes").as_bool(), true);
  EXPECT_EQ(scalar("Off").as_bool(), false);
  EXPECT_EQ(scalar("True").as_bool(), true);
  EXPECT_TRUE(scalar("~").is_none());
  EXPECT_TRUE(scalar("null").is_none());
  EXPECT_TRUE(scalar("").is_none());
  EXPECT_EQ(scalar("'12'").as_str(), "12");
  EXPECT_EQ(scalar("\"true\"").as_str(), "true");
  EXPECT_EQ(scalar("!!str 5").as_str(), "5");
  EXPECT_EQ(scalar("hello world").as_str(), "hello world");
  EXPECT_EQ(scalar("1.2.3").as_str(), "1.2.3");
}

TEST(XacroYamlValues, UnitTagsAreExpressions) {
  EXPECT_DOUBLE_EQ(scalar("!degrees 180").as_double(), M_PI);
  EXPECT_EQ(scalar("!degrees 90.0").as_double(), 90.0 * (M_PI / 180.0));
  EXPECT_DOUBLE_EQ(scalar("!radians pi/4").as_double(), M_PI / 4);
  EXPECT_DOUBLE_EQ(scalar("!degrees 2*45").as_double(), M_PI / 2);
  EXPECT_THROW(scalar("!degrees nonsense("), ProcessError);
  EXPECT_THROW(scalar("!meters 1"), ProcessError);
}

TEST(XacroYamlValues, MapsAllowAttributeAccessListsNest) {
  const Value v = load_yaml_text("a:\n  b: [1, {c: 2}]\n3: three\n");
  ASSERT_EQ(v.kind(), Value::Kind::Dict);
  EXPECT_TRUE(v.as_dict().attribute_access);
  const Value& b = *v.as_dict().find(Value::string("a"))->as_dict().find(Value::string("b"));
  ASSERT_EQ(b.as_list().size(), 2u);
  EXPECT_TRUE(b.as_list()[1].as_dict().attribute_access);
  EXPECT_EQ(v.as_dict().find(Value::integer(3))->as_str(), "three");
  EXPECT_TRUE(load_yaml_text("").is_none());
  EXPECT_THROW(load_yaml_text("a: [1,"), ProcessError);
}

}  // namespace
}  // namespace lcm_control::xacro

namespace lcm_control::xacro {
namespace {

// An anchor bomb (issue 51): nine levels, each a list aliasing the one before ten times, is 10^9 leaves if copied.
// Aliases are the anchored value itself, as PyYAML makes them: shared, so it reads at once.
TEST(XacroYamlValues, AnchorsAreSharedNotCopied) {
  std::string text = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int k = 1; k <= 9; ++k) {
    text += "a" + std::to_string(k) + ": &a" + std::to_string(k) + " [";
    for (int r = 0; r < 10; ++r) text += (r ? ", *a" : "*a") + std::to_string(k - 1);
    text += "]\n";
  }
  const auto t0 = std::chrono::steady_clock::now();
  const Value v = load_yaml_text(text);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const Value& top = *v.as_dict().find(Value::string("a9"));
  ASSERT_EQ(top.as_list().size(), 10u);
  EXPECT_EQ(&top.as_list()[0].as_list(), &top.as_list()[9].as_list()) << "the same list, not a copy";
  EXPECT_EQ(&top.as_list()[0].as_list(), &v.as_dict().find(Value::string("a8"))->as_list());
  std::printf("anchor bomb of 10^9 leaves read in %.2f ms\n", ms);
}

}  // namespace
}  // namespace lcm_control::xacro
