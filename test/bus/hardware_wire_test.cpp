// The array-count checks that run on hardware messages before lcm-gen's
// decoders see them: negative, huge and oversized counts are refused.
#include "bus/hardware_wire.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "bus/messages.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/pid_gains_t.hpp"
#include "bus/bus.hpp"

using namespace lcm_control;

namespace {

template <class Msg>
std::vector<uint8_t> bytes_of(const Msg& m) {
  std::vector<uint8_t> b(size_t(m.getEncodedSize()));
  m.encode(b.data(), 0, int(b.size()));
  return b;
}

void set_count(std::vector<uint8_t>& b, size_t offset, uint32_t n) {
  for (int k = 0; k < 4; ++k) b[offset + k] = uint8_t(n >> (24 - 8 * k));
}

}  // namespace

TEST(HardwareWire, AStateWithACountItHoldsPassesAndForgedCountsAreRefused) {
  hardware_state_t s{};
  resize(s, 2);
  s.name = {"a", "b"};
  std::vector<uint8_t> b = bytes_of(s);
  EXPECT_EQ(check_hardware_state_bytes(b.data(), b.size(), 2), "");
  const size_t at = 8 + 8 + 8 + 8 + 1 + 4 + 1 + 8;
  set_count(b, at, 0xFFFFFFFFu);
  EXPECT_EQ(check_hardware_state_bytes(b.data(), b.size(), 2),
            "num_actuators -1 is not between 0 and 2 (the robot's actuators)");
  set_count(b, at, 67108866u);  // one bit flipped from 2
  EXPECT_NE(check_hardware_state_bytes(b.data(), b.size(), 2).find("num_actuators 67108866"), std::string::npos);
  set_count(b, at, 2);
  EXPECT_NE(check_hardware_state_bytes(b.data(), 20, 2).find("too short"), std::string::npos);
  EXPECT_NE(check_hardware_state_bytes(b.data(), at + 4 + 40, 2).find("does not fit in"), std::string::npos);
}

TEST(HardwareWire, CommandCountsAreBoundedByTheRobotAndTheMessageSize) {
  hardware_command_t c{};
  resize(c, 3);
  c.name = {"x", "y", "z"};
  std::vector<uint8_t> b = bytes_of(c);
  EXPECT_EQ(check_hardware_command_bytes(b.data(), b.size(), 3), "");
  EXPECT_NE(check_hardware_command_bytes(b.data(), b.size(), 2).find("not between 0 and 2"), std::string::npos);
  set_count(b, 32, 0x80000000u);
  EXPECT_NE(check_hardware_command_bytes(b.data(), b.size(), 3).find("-2147483648"), std::string::npos);
}

namespace {
struct StateCounter {
  int good = 0;
  void on(const lcm::ReceiveBuffer*, const std::string&, const joint_state_t* m) { good += m->num_joints == 2; }
};
}  // namespace

TEST(GuardedDecode, APayloadWhoseDecoderWouldThrowNeverReachesTheHandler) {
  lcm::LCM lc("memq://");
  StateCounter counter;
  subscribe_guarded<&StateCounter::on>(lc, "joint_states", &counter);
  joint_state_t s{};
  resize(s, 2);
  s.name = {"j1", "j2"};
  std::vector<uint8_t> b = bytes_of(s);
  for (uint32_t n : {0xFFFFFFFFu, 0x80000000u}) {  // lcm-gen's decoder resizes with these and throws
    std::vector<uint8_t> bad = b;
    for (int k = 0; k < 4; ++k) bad[16 + k] = uint8_t(n >> (24 - 8 * k));
    joint_state_t probe;
    EXPECT_FALSE(decode_guarded(probe, bad.data(), bad.size()));
    lc.publish("joint_states", bad.data(), unsigned(bad.size()));
    ASSERT_NO_THROW(lc.handleTimeout(0));
  }
  EXPECT_EQ(counter.good, 0);
  lc.publish("joint_states", b.data(), unsigned(b.size()));
  lc.handleTimeout(0);
  EXPECT_EQ(counter.good, 1);
}

// A forged array count on any type (here a request's names, 67,108,866 for 1) is refused by the walk along the schema
// before lcm-gen's decoder allocates 67 million strings (it took over a second; the fuzz test found it).
TEST(GuardedDecode, ForgedCountsOfAnyTypeAreRefusedBeforeDecoding) {
  cm_request_t r = cm_request(cm_request_t::LOAD, {"j1_controller"});
  std::vector<uint8_t> b(size_t(r.getEncodedSize()));
  r.encode(b.data(), 0, int(b.size()));
  EXPECT_TRUE(wire_fits<cm_request_t>(b.data(), b.size()));
  const size_t at = 8 + 8 + 8 + 4 + 1 + 1;  // fingerprint, utime, request_id, client "" (length 1 + NUL), op
  ASSERT_EQ(b[at + 3], 1);                   // num_names
  for (int32_t forged : {67108866, -1, 2}) {
    for (int k = 0; k < 4; ++k) b[at + size_t(k)] = uint8_t(uint32_t(forged) >> (24 - 8 * k));
    EXPECT_FALSE(wire_fits<cm_request_t>(b.data(), b.size())) << forged;
    cm_request_t out;
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_FALSE(decode_guarded(out, b.data(), b.size())) << forged;
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::milliseconds(10)) << forged;
  }
  // Truncated anywhere, extended, or a string whose length says more than there is: refused too.
  for (size_t n = 0; n < b.size(); ++n) EXPECT_FALSE(wire_fits<cm_request_t>(b.data(), n)) << n;
  joint_trajectory_t t{};
  t.num_points = 1;
  t.points.resize(1);
  t.points[0].num_positions = 2;
  t.points[0].positions = {1, 2};
  std::vector<uint8_t> tb(size_t(t.getEncodedSize()));
  t.encode(tb.data(), 0, int(tb.size()));
  EXPECT_TRUE(wire_fits<joint_trajectory_t>(tb.data(), tb.size()));
  tb[tb.size() - 4 - 4 - 16 - 4] = 0x7f;  // point 0's num_positions (then 2 doubles and two empty arrays), made huge
  EXPECT_FALSE(wire_fits<joint_trajectory_t>(tb.data(), tb.size()));
}

// A string with a NUL inside decodes, but lcm-gen would then encode it only up to that NUL while sizing it by its
// length, so the message could not be published on (libFuzzer found it on pid_gains_t): refused before decoding.
TEST(GuardedDecode, AStringWithANulInsideIsRefused) {
  pid_gains_t g{};
  g.joint = "j1";
  std::vector<uint8_t> b(size_t(g.getEncodedSize()));
  g.encode(b.data(), 0, int(b.size()));
  pid_gains_t out;
  EXPECT_TRUE(decode_guarded(out, b.data(), b.size()));
  const size_t owner = 8 + 8 + 8;  // fingerprint, utime, request_id: then owner "" (length 1, NUL), joint "j1"
  ASSERT_EQ(b[owner + 3], 1);
  b[owner + 4 + 1 + 4] = 0;  // joint "j1" becomes "\01"
  EXPECT_FALSE(decode_guarded(out, b.data(), b.size()));
  b[owner + 4 + 1 + 4] = 'j';
  b[owner + 4 + 1 + 4 + 2] = 'x';  // joint's terminating NUL overwritten
  EXPECT_FALSE(decode_guarded(out, b.data(), b.size()));
}

// lcm-gen's decoder resizes an array only when its count is not 0: into a reused message, an empty array after a full
// one kept the old elements (the controller manager then dropped every later state as malformed, found by the fuzz
// over LCM once hardware_state_t had sensor values). Every array, nested ones too, now matches its count.
TEST(GuardedDecode, AReusedMessageKeepsNoElementsOfTheOneBefore) {
  hardware_state_t with{};
  resize(with, 2);
  with.sensor_interface = {"imu/orientation.x"};
  with.sensor_value = {0.5};
  with.num_sensor_values = 1;
  hardware_state_t without{};
  resize(without, 0);
  hardware_state_t out;
  ASSERT_TRUE(decode_guarded(out, bytes_of(with).data(), bytes_of(with).size()));
  ASSERT_TRUE(decode_guarded(out, bytes_of(without).data(), bytes_of(without).size()));
  EXPECT_EQ(out.num_sensor_values, 0);
  EXPECT_TRUE(out.sensor_value.empty());
  EXPECT_TRUE(out.sensor_interface.empty());
  EXPECT_TRUE(out.name.empty());
  EXPECT_EQ(check(out), "");
  joint_trajectory_t t{};
  t.num_joints = 1;
  t.joint_names = {"j"};
  t.num_points = 1;
  t.points.resize(1);
  t.points[0].num_positions = 1;
  t.points[0].positions = {1.0};
  joint_trajectory_t t_out;
  ASSERT_TRUE(decode_guarded(t_out, bytes_of(t).data(), bytes_of(t).size()));
  t.points[0].num_positions = 0;
  t.points[0].positions.clear();
  ASSERT_TRUE(decode_guarded(t_out, bytes_of(t).data(), bytes_of(t).size()));
  EXPECT_TRUE(t_out.points[0].positions.empty());  // nested
}

TEST(ActuatorBinding, MatchesByNameInAnyOrderAndNamesWhatDiffers) {
  const std::vector<std::string> ours{"a", "b", "c"};
  const ActuatorBinding same = bind_actuators(ours, {"c", "a", "b"});
  EXPECT_EQ(same.slot, (std::vector<int>{1, 2, 0}));
  EXPECT_TRUE(same.unknown.empty() && same.missing.empty() && same.repeated.empty());
  EXPECT_EQ(same.problem(false), "");

  const ActuatorBinding extra = bind_actuators(ours, {"a", "x", "b", "c"});
  EXPECT_EQ(extra.slot, (std::vector<int>{0, 2, 3}));
  EXPECT_EQ(extra.unknown, (std::vector<std::string>{"x"}));
  EXPECT_EQ(extra.problem(true), "");
  EXPECT_EQ(extra.problem(false), "unknown actuator(s) 'x'");

  const ActuatorBinding bad = bind_actuators(ours, {"b", "b", "y"});
  EXPECT_EQ(bad.slot, (std::vector<int>{-1, 0, -1}));
  EXPECT_EQ(bad.problem(false), "missing actuator(s) 'a', 'c'; unknown actuator(s) 'y'; actuator(s) 'b' listed twice");
}
