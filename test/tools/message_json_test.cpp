#include "tools/lib/messages/message_json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lcm_control/visit.hpp"

namespace lcm_control::tools {
namespace {

// Gives every field of a message a value of its own: numbers from a counter, strings "s<k>", two elements in each
// variable array (so every count is 2), nested messages filled the same way.
class Fill {
 public:
  explicit Fill(int& k) : k_(k) {}
  template <class T>
  void value(const char*, T& x) {
    if constexpr (std::is_same_v<T, std::string>) x = "s" + std::to_string(k_++);
    else if constexpr (std::is_floating_point_v<T>) x = T(k_++) + T(0.25);
    else x = T(k_++ % 100);
  }
  void count(const char*, int32_t& n) { n = 2; }
  template <class T>
  void list(const char*, std::vector<T>& xs, const char*) {
    xs.resize(2);
    for (auto& x : xs) value("", x);
  }
  template <class T>
  void matrix(const char*, std::vector<std::vector<T>>& xs, const char*, int inner) {
    xs.assign(2, std::vector<T>(size_t(inner)));
    for (auto& row : xs)
      for (auto& x : row) value("", x);
  }
  template <class S>
  void structs(const char*, std::vector<S>& xs, const char*) {
    xs.resize(2);
    for (auto& x : xs) visit(x, *this);
  }
  template <class S>
  void nested(const char*, S& x) {
    visit(x, *this);
  }

 private:
  int& k_;
};

template <class Msg>
std::vector<uint8_t> encode(const Msg& m) {
  std::vector<uint8_t> out(size_t(m.getEncodedSize()));
  m.encode(out.data(), 0, int(out.size()));
  return out;
}

TEST(MessageJson, EveryTypeGoesToJsonAndBackToTheSameBytes) {
  int types = 0;
  for_each_type([&](auto tag) {
    using Msg = typename decltype(tag)::type;
    Msg m{};
    int k = 1;
    Fill fill(k);
    visit(m, fill);
    const auto bytes = encode(m);
    const auto json = message_to_json(bytes.data(), bytes.size());
    const auto back = message_from_json(Msg::getTypeName(), nlohmann::json::parse(json.dump()), -1);
    EXPECT_EQ(back, bytes) << Msg::getTypeName() << ": " << json.dump();
    ++types;
  });
  EXPECT_GE(types, 26);
}

TEST(MessageJson, FieldsInSchemaOrderWithoutCountsAndNonFiniteAsNull) {
  joint_state_t m{};
  m.utime = 5;
  m.num_joints = 2;
  m.name = {"j1", "j2"};
  m.position = {0.5, std::numeric_limits<double>::quiet_NaN()};
  m.velocity = {0, std::numeric_limits<double>::infinity()};
  m.effort = {1, 2};
  const auto bytes = encode(m);
  EXPECT_EQ(message_to_json(bytes.data(), bytes.size()).dump(),
            R"({"utime":5,"name":["j1","j2"],"position":[0.5,null],"velocity":[0.0,null],"effort":[1.0,2.0]})");
}

TEST(MessageJson, ErrorsNameTheTypeAndField) {
  const uint8_t junk[16] = {1, 2, 3, 4, 5, 6, 7, 8};
  EXPECT_THROW(message_to_json(junk, sizeof junk), std::runtime_error);
  EXPECT_THROW(message_to_json(junk, 4), std::runtime_error);
  try {
    message_from_json("float64_t", {{"dat", 1}}, 0);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("dat"), std::string::npos) << e.what();
  }
  EXPECT_THROW(message_from_json("float64_t", {{"data", "fast"}}, 0), std::invalid_argument);
  EXPECT_THROW(message_from_json("float64_t", nlohmann::json::array(), 0), std::invalid_argument);
  EXPECT_THROW(message_from_json("no_such_t", nlohmann::json::object(), 0), std::invalid_argument);
  // utime not given is the default; arrays size their counts.
  const auto bytes = message_from_json("float64_array_t", {{"data", {1.5, 2.5}}}, 77);
  float64_array_t m{};
  ASSERT_GE(m.decode(bytes.data(), 0, int(bytes.size())), 0);
  EXPECT_EQ(m.utime, 77);
  EXPECT_EQ(m.size, 2);
  EXPECT_EQ(m.data[1], 2.5);
}

}  // namespace
}  // namespace lcm_control::tools

// The page labels rows and builds the gains panel from this, so a new field in lcmtypes/ needs no edit in the page.
TEST(MessageJson, SchemaListsEveryFieldWithItsTypeSizeLabelsAndUnit) {
  const auto s = lcm_control::tools::schema_json();
  EXPECT_EQ(s["joint_state_t"]["position"],
            (nlohmann::ordered_json{{"type", "double"}, {"count", "num_joints"}, {"labels", "name"}, {"unit", "rad or m"}}));
  EXPECT_EQ(s["joint_state_t"]["name"], (nlohmann::ordered_json{{"type", "string"}, {"count", "num_joints"}}));
  EXPECT_EQ(s["link_poses_t"]["position"]["labels"], "name");
  EXPECT_EQ(s["link_poses_t"]["position"]["components"], "x y z");
  std::vector<std::string> gains;
  for (const auto& [field, info] : s["pid_gains_t"].items())
    if (info["type"] == "double") gains.push_back(field);
  EXPECT_EQ(gains, (std::vector<std::string>{"p", "i", "d", "i_clamp_min", "i_clamp_max"}));
  EXPECT_EQ(s["joint_trajectory_t"]["points"]["nested"], "trajectory_point_t");
  EXPECT_FALSE(s["joint_trajectory_t"]["points"].contains("labels"));  // no string array of its size names them
  size_t types = 0;
  lcm_control::for_each_type([&](auto) { ++types; });
  EXPECT_EQ(s.size(), types);
}
