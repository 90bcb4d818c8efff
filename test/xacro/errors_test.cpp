// The problems a user can act on: each names what is wrong, where (file:line), and the chain of macro calls and
// includes that led there.
#include <gtest/gtest.h>
#include <pthread.h>

#include <string>

#include "test/xacro/xacro_test_util.hpp"

namespace lcm_control::xacro {
namespace {

using testing::error_of;

const char* const kHead = "<?xml version=\"1.0\"?>\n<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\" name=\"r\">\n";

std::string robot(const std::string& lines) { return kHead + lines + "</robot>\n"; }

#define EXPECT_CONTAINS(text, part) EXPECT_NE((text).find(part), std::string::npos) << "in:\n" << (text)

TEST(XacroErrors, UndefinedPropertyInAMacroNamesTheChain) {
  const std::string msg = error_of(robot("<xacro:include filename=\"defs.xacro\"/>\n"
                                         "<xacro:outer/>\n"),
                                   {{"defs.xacro", "<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
                                                   "<xacro:macro name=\"inner\" params=\"a\">\n"
                                                   "  <link name=\"${a}_${missing}\"/>\n"
                                                   "</xacro:macro>\n"
                                                   "<xacro:macro name=\"outer\">\n"
                                                   "  <xacro:inner a=\"x\"/>\n"
                                                   "</xacro:macro>\n</robot>\n"}});
  EXPECT_EQ(msg,
            "defs.xacro:3: NameError: name 'missing' is not defined\n"
            "when evaluating expression 'missing'\n"
            "  when instantiating macro 'inner' (defs.xacro:2) at defs.xacro:6\n"
            "  when instantiating macro 'outer' (defs.xacro:5) at main.xacro:4");
}

TEST(XacroErrors, ErrorInAnIncludedFileNamesTheInclude) {
  const std::string msg = error_of(robot("<xacro:include filename=\"sub/a.xacro\"/>\n"),
                                   {{"sub/a.xacro", "<robot>\n<x v=\"${1/0}\"/>\n</robot>\n"}});
  EXPECT_CONTAINS(msg, "sub/a.xacro:2: ZeroDivisionError");
  EXPECT_CONTAINS(msg, "when evaluating expression '1/0'");
  EXPECT_CONTAINS(msg, "\n  in file included from main.xacro:3");
}

TEST(XacroErrors, UnknownMacroAndUnsupportedXacroTag) {
  EXPECT_CONTAINS(error_of(robot("<xacro:nope/>\n")), "main.xacro:3: unknown macro name: xacro:nope");
  EXPECT_CONTAINS(error_of(robot("<xacro:for each=\"x\"/>\n")), "unknown macro name: xacro:for");
}

TEST(XacroErrors, UndefinedArgNamesIt) {
  const std::string msg = error_of(robot("<a v=\"$(arg robot_name)\"/>\n"));
  EXPECT_CONTAINS(msg, "main.xacro:3: Undefined substitution argument robot_name");
  EXPECT_CONTAINS(msg, "robot_name:=VALUE");
  EXPECT_CONTAINS(error_of(robot("<a v=\"${xacro.arg('zz')}\"/>\n")), "KeyError: 'zz'");
}

TEST(XacroErrors, MissingPackageNamesItAndTheSearchNote) {
  const std::string msg = error_of(robot("<xacro:include filename=\"$(find no_such_pkg)/x.xacro\"/>\n"));
  EXPECT_CONTAINS(msg, "main.xacro:3: package 'no_such_pkg' not found ($(find no_such_pkg))\nsearched: ");
}

TEST(XacroErrors, BadExpressionShowsItAndThePythonError) {
  EXPECT_CONTAINS(error_of(robot("<a v=\"${1 +}\"/>\n")), "main.xacro:3: SyntaxError");
  EXPECT_CONTAINS(error_of(robot("<a v=\"${1 +}\"/>\n")), "when evaluating expression '1 +'");
  EXPECT_CONTAINS(error_of(robot("<a>\n\n  ${'a' + 1}</a>\n")), "main.xacro:5: TypeError");
  EXPECT_CONTAINS(error_of(robot("<a v=\"${x\"/>\n")), "invalid expression: ${x");
}

TEST(XacroErrors, ConditionThatIsNotBoolean) {
  EXPECT_CONTAINS(error_of(robot("<xacro:if value=\"maybe\"><a/></xacro:if>\n")),
                  "main.xacro:3: Xacro conditional \"maybe\" evaluated to \"maybe\", which is not a boolean "
                  "expression.");
}

TEST(XacroErrors, IncludeCycleIsAnErrorNotAHang) {
  const std::string msg = error_of(robot("<xacro:include filename=\"a.xacro\"/>\n"),
                                   {{"a.xacro", "<robot xmlns:xacro=\"x\">\n<xacro:include filename=\"b.xacro\"/>\n</robot>"},
                                    {"b.xacro", "<robot xmlns:xacro=\"x\">\n<xacro:include filename=\"a.xacro\"/>\n</robot>"}});
  EXPECT_CONTAINS(msg, "b.xacro:2: include cycle: main.xacro -> a.xacro -> b.xacro -> a.xacro");
  EXPECT_CONTAINS(msg, "in file included from a.xacro:2");
}

TEST(XacroErrors, MissingFileAndXmlSyntax) {
  EXPECT_CONTAINS(error_of(robot("<xacro:include filename=\"gone.xacro\"/>\n")),
                  "main.xacro:3: No such file or directory: gone.xacro");
  EXPECT_CONTAINS(error_of(robot("<xacro:include filename=\"bad.xacro\"/>\n"),
                           {{"bad.xacro", "<robot>\n<a>\n</b>\n</robot>"}}),
                  "bad.xacro:3: XML parsing error: mismatched tag\n  in file included from main.xacro:3");
  EXPECT_CONTAINS(error_of("<robot>\n<a></robot>"), "main.xacro:2: XML parsing error: mismatched tag");
}

// An include or a YAML file that names a FIFO or a device is refused at once, never waited on or read without end.
TEST(XacroErrors, IncludeOrYamlThatIsNotARegularFileIsRefusedAtOnce) {
  EXPECT_CONTAINS(error_of(robot("<xacro:include filename=\"/dev/zero\"/>\n")),
                  "main.xacro:3: /dev/zero is not a regular file (a pipe, socket or device); name the file itself");
  EXPECT_CONTAINS(error_of(robot("<xacro:property name=\"y\" value=\"${xacro.load_yaml('/dev/null')}\"/>\n"
                                 "<a v=\"${y}\"/>\n")),
                  "/dev/null is not a regular file");
  EXPECT_CONTAINS(error_of(robot("<xacro:include filename=\"sub\"/>\n"), {{"sub/x.xacro", "<robot/>"}}),
                  "sub is a folder, not a file");
}

TEST(XacroErrors, MacroParameterProblems) {
  const std::string defs = "<xacro:macro name=\"m\" params=\"a *blk\"><x a=\"${a}\"/></xacro:macro>\n";
  EXPECT_CONTAINS(error_of(robot(defs + "<xacro:m a=\"1\" b=\"2\"><o/></xacro:m>\n")),
                  "main.xacro:4: Invalid parameter \"b\" of macro 'm'");
  EXPECT_CONTAINS(error_of(robot(defs + "<xacro:m><o/></xacro:m>\n")), "Undefined parameters [a] of macro 'm'");
  EXPECT_CONTAINS(error_of(robot(defs + "<xacro:m a=\"1\"/>\n")), "Not enough blocks for macro 'm'");
  EXPECT_CONTAINS(error_of(robot(defs + "<xacro:m a=\"1\"><o/><p/></xacro:m>\n")), "Unused block \"p\"");
  EXPECT_CONTAINS(error_of(robot("<xacro:macro name=\"f\" params=\"v:=^\"/>\n<xacro:f/>\n")),
                  "Undefined property to forward: v");
  EXPECT_CONTAINS(error_of(robot("<xacro:insert_block name=\"nothing\"/>\n")), "Undefined block \"nothing\"");
}

TEST(XacroErrors, PropertyProblems) {
  EXPECT_CONTAINS(error_of(robot("<xacro:property name=\"a\" value=\"${b}\"/>\n<xacro:property name=\"b\" "
                                 "value=\"${a}\"/>\n<x v=\"${a}\"/>\n")),
                  "circular variable definition: a -> b -> a");
  EXPECT_CONTAINS(error_of(robot("<xacro:property name=\"1a\" value=\"1\"/>\n")),
                  "Property names must be valid python identifiers: 1a");
  EXPECT_CONTAINS(error_of(robot("<xacro:property name=\"a\" value=\"1\"/>\n<xacro:property name=\"a\" "
                                 "remove=\"true\"/>\n<x v=\"${a}\"/>\n")),
                  "main.xacro:5: NameError: name 'a' is not defined");
  EXPECT_CONTAINS(error_of(robot("<xacro:property/>\n")), "xacro:property: missing attribute 'name'");
}

TEST(XacroErrors, FatalAndInfiniteRecursion) {
  EXPECT_CONTAINS(error_of(robot("<a v=\"${xacro.fatal('stop', 1)}\"/>\n")), "main.xacro:3: stop 1");
  EXPECT_CONTAINS(error_of(robot("<xacro:macro name=\"r\"><xacro:r/></xacro:macro>\n<xacro:r/>\n")),
                  "maximum recursion depth exceeded");
}

// Runs f on a thread with a stack of `bytes` (a quarter of a default thread's 8 MiB): the limits must hold there.
template <class F>
std::string on_small_stack(size_t bytes, F f) {
  struct Job {
    F f;
    std::string out;
  } job{std::move(f), {}};
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, bytes);
  pthread_t t;
  const int rc = pthread_create(
      &t, &attr,
      [](void* p) -> void* {
        auto* j = static_cast<Job*>(p);
        j->out = j->f();
        return nullptr;
      },
      &job);
  pthread_attr_destroy(&attr);
  if (rc != 0) return "pthread_create failed";
  pthread_join(t, nullptr);
  return job.out;
}

// Hostile nesting (issue 51): far past any real file, each refused with file:line and the limit, never a crash, even
// on a thread with a quarter of the usual stack.
TEST(XacroErrors, DeepNestingIsRefusedWithTheLimitNotACrash) {
  const size_t kStack = 2u << 20;
  auto expr = [](const std::string& e) { return robot("<a v=\"${" + e + "}\"/>\n"); };
  const std::string parens = std::string(5000, '(') + "1" + std::string(5000, ')');
  std::string chain = "1";
  for (int k = 0; k < 20000; ++k) chain += "+1";
  const struct {
    const char* what;
    std::string text;
    const char* expected;
  } cases[] = {
      {"5,000 parentheses", expr(parens), "nests deeper than 400 levels"},
      {"20,000 unary minus", expr(std::string(20000, '-') + "1"), "nests deeper than 400 levels"},
      {"20,000 chained +", expr(chain), "nests deeper than 400 levels"},
      {"20,000 not", expr([] {
         std::string s;
         for (int k = 0; k < 20000; ++k) s += "not ";
         return s + "1";
       }()),
       "nests deeper than 400 levels"},
      {"a lambda calling itself", expr("(lambda f: f(f))(lambda f: f(f))"), "maximum recursion depth exceeded"},
  };
  for (const auto& c : cases) {
    const std::string msg = on_small_stack(kStack, [&] { return error_of(c.text); });
    EXPECT_CONTAINS(msg, "main.xacro:3: RecursionError") << c.what;
    EXPECT_CONTAINS(msg, c.expected) << c.what;
  }
  std::string deep;
  for (int k = 0; k < 10000; ++k) deep += "<a>";
  for (int k = 0; k < 10000; ++k) deep += "</a>";
  const std::string msg = on_small_stack(kStack, [&] { return error_of(robot(deep + "\n")); });
  EXPECT_CONTAINS(msg, "main.xacro");
  EXPECT_CONTAINS(msg, "elements nest deeper than 1000 levels");
  // What real files do stays well inside: 300 levels of parentheses, 300 chained operators, 900 nested elements.
  EXPECT_EQ(on_small_stack(kStack, [&] { return error_of(expr(std::string(300, '(') + "1" + std::string(300, ')'))); }),
            "");
  std::string some = "1";
  for (int k = 0; k < 300; ++k) some += "*1";
  EXPECT_EQ(on_small_stack(kStack, [&] { return error_of(expr(some)); }), "");
  std::string nested;
  for (int k = 0; k < 900; ++k) nested += "<a>";
  for (int k = 0; k < 900; ++k) nested += "</a>";
  EXPECT_EQ(on_small_stack(kStack, [&] { return error_of(robot(nested + "\n")); }), "");
}

TEST(XacroErrors, TopFileMissing) {
  try {
    expand_file("/nonexistent/robot.urdf.xacro", Options());
    FAIL();
  } catch (const XacroError& e) {
    EXPECT_EQ(std::string(e.what()), "No such file or directory: /nonexistent/robot.urdf.xacro");
  }
}

TEST(XacroWarnings, UnknownAttributesAndXacroWarningGoToTheMessageCallback) {
  std::vector<std::string> messages;
  testing::expand_text(robot("<xacro:property name=\"a\" value=\"1\" typo=\"2\"/>\n<v w=\"${xacro.warning('careful')}\"/>\n"),
                       {}, {}, &messages);
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_CONTAINS(messages[0], "main.xacro:3: warning: xacro:property: unknown attribute(s): typo");
  EXPECT_EQ(messages[1], "warning: careful");
  EXPECT_CONTAINS(messages[2], "main.xacro:4");
}

}  // namespace
}  // namespace lcm_control::xacro
