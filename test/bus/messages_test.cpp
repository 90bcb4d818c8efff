// The wire contract: a header per lcm type, a class per type in the lcm-spy jar,
// and the consistency checks that keep LCM's encoder from crashing.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <set>

#include "bus/messages.hpp"
#include "test/support/process.hpp"

namespace fs = std::filesystem;
namespace lt = lcm_control::testing;

namespace {
std::set<std::string> lcm_type_names() {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(lt::source("lcmtypes")))
    if (e.path().extension() == ".lcm") names.insert(e.path().stem().string());
  return names;
}
}  // namespace

TEST(LcmTypes, AGeneratedHeaderForEveryType) {
  const auto names = lcm_type_names();
  ASSERT_GE(names.size(), 15u);
  const fs::path gen = fs::path(LCM_CONTROL_BIN_DIR).parent_path() / "lcmtypes/cpp/lcm_control";
  for (const auto& n : names) EXPECT_TRUE(fs::exists(gen / (n + ".hpp"))) << n;
}

TEST(LcmTypes, TheJarHasAClassForEveryType) {
  const fs::path jar = fs::path(LCM_CONTROL_BIN_DIR).parent_path() / "share/lcm_control_types.jar";
  if (!fs::exists(jar)) GTEST_SKIP() << "no JDK at build time, so no jar";
  lt::ChildProcess p({"/usr/bin/jar", "tf", jar.string()});
  ASSERT_EQ(p.wait(60), 0) << p.output();
  const std::string listing = p.output();
  for (const auto& n : lcm_type_names())
    EXPECT_NE(listing.find("lcm_control/" + n + ".class"), std::string::npos) << n << " missing from the jar";
}

TEST(Messages, CheckCatchesLengthMismatchAndNaN) {
  lcm_control::joint_state_t js;
  lcm_control::resize(js, 2);
  EXPECT_EQ(lcm_control::check(js), "");
  js.num_joints = 3;
  EXPECT_NE(lcm_control::check(js), "");

  lcm_control::hardware_command_t c;
  lcm_control::resize(c, 1);
  c.name[0] = "a1";
  c.mode[0] = lcm_control::hardware_command_t::MODE_POSITION;
  c.command[0] = 1.0;
  EXPECT_EQ(lcm_control::check(c), "");
  c.command[0] = NAN;
  EXPECT_NE(lcm_control::check(c).find("'a1' command is NaN"), std::string::npos);
  c.command[0] = 0;
  c.mode[0] = 9;
  EXPECT_NE(lcm_control::check(c).find("unknown mode 9"), std::string::npos);

  lcm_control::float64_array_t a;
  a.size = 2;
  a.data = {1.0};
  EXPECT_NE(lcm_control::check(a), "");
}
