// Acceptance: every command of ../shared/ros2_robots/*/expected/xacro_commands.json (six real ROS 2 robot packages
// beside the checkout, with the official xacro's output) expands through the library to the expected URDF: the same
// elements, attributes (in order) and text, compared tree by tree with the path of the first difference; and the
// same bytes, comments included. Skipped when the folder is absent.
#include <gtest/gtest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "xacro/xacro.hpp"
#include "test/xacro/xacro_test_util.hpp"
#include "xacro/xml_dom.hpp"

namespace lcm_control::xacro {
namespace {

namespace fs = std::filesystem;

const std::string kRobots = LCM_CONTROL_SOURCE_DIR "/../shared/ros2_robots";

struct Command {
  std::string name;  // gtest-safe: robot_title
  fs::path robot;
  std::string input, expected;
  std::vector<std::string> args;
};

std::vector<Command> commands() {
  std::vector<Command> out;
  std::error_code ec;
  if (!fs::is_directory(kRobots, ec)) return {Command{"absent", {}, {}, {}, {}}};
  std::vector<fs::path> robots;
  for (const auto& entry : fs::directory_iterator(kRobots, ec))
    if (fs::exists(entry.path() / "expected" / "xacro_commands.json")) robots.push_back(entry.path());
  std::sort(robots.begin(), robots.end());
  for (const fs::path& robot : robots) {
    std::ifstream in(robot / "expected" / "xacro_commands.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& c : j.at("commands")) {
      Command cmd;
      cmd.robot = fs::canonical(robot);
      cmd.input = c.at("input");
      cmd.expected = c.at("expected");
      for (const auto& a : c.at("args")) cmd.args.push_back(a);
      std::string stem = fs::path(cmd.expected).stem().string();
      cmd.name = robot.filename().string() + "_" + stem;
      for (char& ch : cmd.name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      out.push_back(cmd);
    }
  }
  return out;
}

bool blank(const std::string& s) { return s.find_first_not_of(" \t\r\n") == std::string::npos; }

// The children that count: elements and non-blank text (comments ignored).
std::vector<const dom::Node*> significant(const dom::Node* n) {
  std::vector<const dom::Node*> out;
  for (const dom::Node* c = n->first; c; c = c->next)
    if (c->is_element() || ((c->is_text() || c->type == dom::NodeType::CData) && !blank(c->data))) out.push_back(c);
  return out;
}

// "" when equal, else the path of the first difference and what differs.
std::string first_difference(const dom::Node* got, const dom::Node* want, const std::string& path) {
  const std::string here = path + "/" + want->name;
  if (got->name != want->name) return fmt::format("{}: element <{}>, expected <{}>", path, got->name, want->name);
  for (size_t i = 0; i < std::max(got->attrs.size(), want->attrs.size()); ++i) {
    if (i >= got->attrs.size()) return fmt::format("{}: attribute {} missing", here, want->attrs[i].name);
    if (i >= want->attrs.size()) return fmt::format("{}: extra attribute {}", here, got->attrs[i].name);
    if (got->attrs[i].name != want->attrs[i].name)
      return fmt::format("{}: attribute #{} is {}, expected {}", here, i + 1, got->attrs[i].name, want->attrs[i].name);
    if (got->attrs[i].value != want->attrs[i].value)
      return fmt::format("{}@{}: \"{}\", expected \"{}\"", here, want->attrs[i].name, got->attrs[i].value,
                         want->attrs[i].value);
  }
  const auto g = significant(got), w = significant(want);
  for (size_t i = 0; i < std::max(g.size(), w.size()); ++i) {
    if (i >= g.size()) return fmt::format("{}: child #{} missing (expected <{}>)", here, i + 1, w[i]->name);
    if (i >= w.size()) return fmt::format("{}: extra child #{} <{}>", here, i + 1, g[i]->name);
    if (g[i]->is_element() != w[i]->is_element()) return fmt::format("{}: child #{} differs in kind", here, i + 1);
    if (!w[i]->is_element()) {
      if (g[i]->data != w[i]->data)
        return fmt::format("{}: text \"{}\", expected \"{}\"", here, g[i]->data, w[i]->data);
      continue;
    }
    std::string d = first_difference(g[i], w[i], here);
    if (!d.empty()) return d;
  }
  return "";
}

class RealRobots : public ::testing::TestWithParam<Command> {};

TEST_P(RealRobots, ExpandsAsTheOfficialXacro) {
  const Command& c = GetParam();
  if (c.name == "absent") GTEST_SKIP() << kRobots << " is absent (the real robots sit beside the checkout in CI)";
  const std::string robot = c.robot.string();
  Options options;
  for (const std::string& a : c.args) options.args.push_back(parse_arg(testing::replace_all(a, "$R", robot)));
  options.find_package = [robot](const std::string& pkg) {
    const std::string dir = robot + "/pkgs/" + pkg;
    return fs::is_directory(dir) ? dir : std::string();
  };
  options.message = [](const std::string& line) { ADD_FAILURE() << "unexpected message: " << line; };
  const Expansion e = expand_file(robot + "/" + c.input, options);
  const std::string expected = testing::replace_all(testing::read((c.robot / c.expected).string()), "@ROBOT_DIR@", robot);

  dom::Arena arena;
  const std::string got_file = "expanded", want_file = c.expected;
  const dom::Node* got = dom::parse(e.xml, &got_file, arena)->first_element();
  const dom::Node* want = dom::parse(expected, &want_file, arena)->first_element();
  const std::string diff = first_difference(got, want, "");
  EXPECT_EQ(diff, "") << c.expected;
  if (diff.empty()) {
    EXPECT_TRUE(e.xml == expected) << c.expected << ": same tree, but the text differs (comments?)";
  }
}

INSTANTIATE_TEST_SUITE_P(Shared, RealRobots, ::testing::ValuesIn(commands()),
                         [](const ::testing::TestParamInfo<Command>& info) { return info.param.name; });

TEST(RealRobotsTiming, Ur5eExpansion) {
  const fs::path robot = kRobots + "/ur5e";
  if (!fs::is_directory(robot)) GTEST_SKIP() << robot << " is absent";
  const std::string r = fs::canonical(robot).string();
  Options options;
  for (std::string a : {"safety_limits:=true", "safety_pos_margin:=0.15", "safety_k_position:=20", "name:=ur",
                        "ur_type:=ur5e", "tf_prefix:="})
    options.args.push_back(parse_arg(a));
  options.args.emplace_back("simulation_controllers", r + "/pkgs/ur_simulation_gz/config/ur_controllers.yaml");
  options.find_package = [r](const std::string& pkg) { return r + "/pkgs/" + pkg; };
  const auto start = std::chrono::steady_clock::now();
  const int runs = 5;
  for (int i = 0; i < runs; ++i) expand_file(r + "/pkgs/ur_simulation_gz/urdf/ur_gz.urdf.xacro", options);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / runs;
  std::printf("UR5e expansion: %.2f ms\n", ms);
  RecordProperty("ur5e_expansion_ms", std::to_string(ms));
  EXPECT_LT(ms, 1000.0);
}

}  // namespace
}  // namespace lcm_control::xacro
