// Field paths: decoding by fingerprint and the flattened (path, value) pairs,
// numbers first, then strings.
#include "tools/lib/messages/fields.hpp"

#include <gtest/gtest.h>

#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/controller_state_t.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/link_poses_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"

using namespace lcm_control;
using namespace lcm_control::tools;

namespace {
template <class Msg>
std::vector<uint8_t> encode(const Msg& m) {
  std::vector<uint8_t> buf(size_t(m.getEncodedSize()));
  m.encode(buf.data(), 0, int(buf.size()));
  return buf;
}
std::vector<std::string> paths(const Decoded& d) {
  std::vector<std::string> p;
  for (const auto& f : d.fields) p.push_back(f.path);
  return p;
}
// The fields of a joint_state_t of two joints named `names`: position 0.1, 0.2, velocity 1.5, -2, effort 3, 4.
Decoded two_joints(const std::vector<std::string>& names, int64_t utime = 0) {
  joint_state_t m{};
  m.utime = utime;
  m.num_joints = 2;
  m.name = names;
  m.position = {0.1, 0.2};
  m.velocity = {1.5, -2};
  m.effort = {3, 4};
  const auto buf = encode(m);
  return decode_fields(buf.data(), buf.size());
}
}  // namespace

TEST(Fields, JointStateColumns) {
  const Decoded d = two_joints({"j1", "j2"}, 1234567890123456);
  ASSERT_TRUE(d.ok()) << d.skip_reason;
  EXPECT_EQ(d.type, "lcm_control.joint_state_t");
  EXPECT_EQ(paths(d), (std::vector<std::string>{"utime", "position[0]", "position[1]", "velocity[0]", "velocity[1]",
                                                "effort[0]", "effort[1]", "name[0]", "name[1]"}));
  EXPECT_EQ(d.fields[0].text(), "1234567890123456");
  EXPECT_EQ(d.fields[1].text(), "0.1");
  EXPECT_EQ(d.fields[4].text(), "-2");
  EXPECT_FALSE(d.fields[6].is_text);
  EXPECT_TRUE(d.fields[8].is_text);
  EXPECT_EQ(d.fields[8].text(), "j2");
}

TEST(Fields, ListRowsTakeTheDashboardsLabelsAndAreSelectedByPathOrLabel) {
  const Decoded d = two_joints({"j1", "j2"});
  ASSERT_TRUE(d.ok()) << d.skip_reason;
  EXPECT_EQ(d.fields[2].name(), "position[j2]");
  EXPECT_EQ(d.fields[0].name(), "utime");
  auto selected = [&](const std::string& wanted) {
    std::vector<std::string> out;
    for (const Field* f : select_fields(d.fields, wanted)) out.push_back(f->path);
    return out;
  };
  EXPECT_EQ(selected("position[j2]"), (std::vector<std::string>{"position[1]"}));
  EXPECT_EQ(selected("position[1]"), (std::vector<std::string>{"position[1]"}));
  EXPECT_EQ(selected("/velocity"), (std::vector<std::string>{"velocity[0]", "velocity[1]"}));
  EXPECT_TRUE(selected("position[j3]").empty());
  EXPECT_TRUE(selected("pos").empty());
  EXPECT_EQ(nearest_fields(d.fields, "postion[j2]", 2), (std::vector<std::string>{"position[j2]", "position[j1]"}));
}

TEST(Fields, RowsWithoutDistinctNamesKeepTheirIndexAsLabel) {
  const Decoded d = two_joints({"j1", "j1"});
  EXPECT_EQ(d.fields[2].name(), "position[1]");
}

TEST(Fields, StringsFollowTheNumbers) {
  trajectory_status_t s{};
  s.utime = 5;
  s.goal_id = 3;
  s.status = trajectory_status_t::GOAL_TOLERANCE_VIOLATED;
  s.message = "goal tolerance violated on joint 'j1': error 0.5, tolerance 0.1";
  s.num_joints = 2;
  s.joint_names = {"j1", "j2"};
  s.desired = {1, 2};
  s.actual = {0.5, 2};
  s.error = {0.5, 0};
  auto buf = encode(s);
  Decoded d = decode_fields(buf.data(), buf.size());
  ASSERT_TRUE(d.ok()) << d.skip_reason;
  EXPECT_EQ(paths(d), (std::vector<std::string>{"utime", "goal_id", "status", "desired[0]", "desired[1]", "actual[0]",
                                                "actual[1]", "error[0]", "error[1]", "message", "joint_names[0]",
                                                "joint_names[1]"}));
  EXPECT_EQ(d.fields[2].text(), "4");
  EXPECT_TRUE(d.fields[9].is_text);
  EXPECT_EQ(d.fields[9].text(), s.message);
  EXPECT_EQ(d.fields[9].value, 0);
  EXPECT_EQ(d.fields[11].text(), "j2");

  controller_state_t c{};
  c.controller = "j2_controller";
  c.joint = "j2";
  c.error = 0.25;
  buf = encode(c);
  d = decode_fields(buf.data(), buf.size());
  const auto p = paths(d);
  ASSERT_EQ(p.size(), 14u);
  EXPECT_EQ(p[4], "error");
  EXPECT_EQ(d.fields[4].text(), "0.25");
  EXPECT_EQ(p[12], "controller");
  EXPECT_EQ(d.fields[12].text(), "j2_controller");
  EXPECT_EQ(p[13], "joint");
  EXPECT_EQ(d.fields[13].text(), "j2");
}

TEST(Fields, CommandsAndNestedTypes) {
  float64_t f{};
  f.data = 3.25;
  auto buf = encode(f);
  Decoded d = decode_fields(buf.data(), buf.size());
  EXPECT_EQ(paths(d), (std::vector<std::string>{"utime", "data"}));
  EXPECT_EQ(d.fields[1].value, 3.25);

  float64_array_t a{};
  a.size = 3;
  a.data = {1, 2, 3};
  buf = encode(a);
  d = decode_fields(buf.data(), buf.size());
  EXPECT_EQ(paths(d), (std::vector<std::string>{"utime", "data[0]", "data[1]", "data[2]"}));

  link_poses_t lp{};
  lp.num_links = 1;
  lp.name = {"base"};
  lp.position = {{1, 2, 3}};
  lp.orientation = {{1, 0, 0, 0}};
  buf = encode(lp);
  d = decode_fields(buf.data(), buf.size());
  EXPECT_EQ(paths(d)[3], "position[base].z");  // rows by link name, columns by the schema's {x y z}
  EXPECT_EQ(d.fields[3].value, 3);
  EXPECT_EQ(paths(d)[4], "orientation[base].w");
  lp.name = {""};  // a name that cannot label a row: by index
  buf = encode(lp);
  d = decode_fields(buf.data(), buf.size());
  EXPECT_EQ(paths(d)[3], "position[0][2]");

  joint_trajectory_t jt{};
  jt.num_joints = 1;
  jt.joint_names = {"j1"};
  jt.num_points = 1;
  jt.points.resize(1);
  jt.points[0].time_from_start = 2;
  jt.points[0].num_positions = 1;
  jt.points[0].positions = {0.5};
  buf = encode(jt);
  d = decode_fields(buf.data(), buf.size());
  EXPECT_EQ(paths(d), (std::vector<std::string>{"utime", "goal_id", "points[0].time_from_start",
                                                "points[0].positions[0]", "joint_names[0]"}));
}

TEST(Fields, SkippedTypesSayWhy) {
  cm_response_t r{};
  r.message = "hello";
  auto buf = encode(r);
  Decoded d = decode_fields(buf.data(), buf.size());
  EXPECT_FALSE(d.ok());
  EXPECT_EQ(d.type, "lcm_control.cm_response_t");
  EXPECT_NE(d.skip_reason.find("no signals"), std::string::npos);

  const std::string junk = "not an lcm message at all";
  d = decode_fields(junk.data(), junk.size());
  EXPECT_FALSE(d.ok());
  EXPECT_EQ(d.type, "");
  EXPECT_NE(d.skip_reason.find("fingerprint"), std::string::npos);

  d = decode_fields(junk.data(), 4);
  EXPECT_NE(d.skip_reason.find("too short"), std::string::npos);

  // A truncated payload of a known type.
  float64_array_t a{};
  a.size = 3;
  a.data = {1, 2, 3};
  buf = encode(a);
  d = decode_fields(buf.data(), buf.size() - 4);
  EXPECT_EQ(d.skip_reason, "malformed payload (decode failed)");
}

TEST(Fields, CsvFileNames) {
  EXPECT_EQ(csv_file_name("joint_states"), "joint_states.csv");
  EXPECT_EQ(csv_file_name("j2_controller/command"), "j2_controller__command.csv");
  EXPECT_EQ(csv_file_name("/robot1/joint_states"), "robot1__joint_states.csv");
}

TEST(Fields, UnitsComeFromTheSchemaComments) {
  EXPECT_EQ(field_unit("lcm_control.joint_state_t", "position[1]"), "rad or m");
  EXPECT_EQ(field_unit("lcm_control.joint_state_t", "effort[0]"), "N*m or N");
  EXPECT_EQ(field_unit("joint_state_t", "utime"), "us");
  EXPECT_EQ(field_unit("lcm_control.link_poses_t", "position[rotor].z"), "m");
  EXPECT_EQ(field_unit("lcm_control.link_poses_t", "orientation[rotor].w"), "");
  EXPECT_EQ(field_unit("lcm_control.joint_trajectory_t", "points[2].velocities[1]"), "rad/s or m/s");
  EXPECT_EQ(field_unit("lcm_control.joint_trajectory_t", "points[0].time_from_start"), "s");
  EXPECT_EQ(field_unit("lcm_control.float64_t", "data"), "");
  EXPECT_EQ(field_unit("lcm_control.no_such_t", "x"), "");
}
