// Bus input a hostile or broken peer can send the controller manager: forged
// array counts on hardware/state are dropped before decoding and the loop goes
// on answering the real hardware.
#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "bus/messages.hpp"
#include "controller_manager/services.hpp"
#include "lcm_control/command_source_t.hpp"
#include "test/controller_manager/rig.hpp"
#include "test/support/lcm_test.hpp"

using lcm_control::testing::Rig;
using namespace lcm_control;

TEST(ControllerManagerHostileInput, ForgedActuatorCountsOnHardwareStateAreDroppedAndTheLoopGoesOn) {
  Rig rig;
  rig.cycle(10);
  std::vector<uint8_t> b(size_t(rig.state.getEncodedSize()));
  rig.state.encode(b.data(), 0, int(b.size()));
  const size_t at = 8 + 8 + 8 + 8 + 1 + 4 + 1 + 8;
  for (uint32_t n : {0xFFFFFFFFu, 67108866u, 0x7FFFFFFFu}) {
    for (int k = 0; k < 4; ++k) b[at + k] = uint8_t(n >> (24 - 8 * k));
    rig.bus.lcm().publish("hardware/state", b.data(), unsigned(b.size()));
    ASSERT_NO_THROW(rig.pump()) << n;
  }
  const size_t answered = rig.commands.size();
  rig.cycle(10);
  EXPECT_EQ(rig.commands.size(), answered + 10);
  EXPECT_EQ(rig.commands.back().step, rig.step - 1);
}

// 2,000 requests and 2,000 command-source requests from a client with a 60 KB name: the log is clipped and rate
// limited (it was 120 MB), every request is still answered.
TEST(ControllerManagerHostileInput, AFloodOfRequestsWithHugeNamesCannotFillTheLog) {
  Rig rig;
  cm::Services services(*rig.cm, rig.bus);
  lcm_control::testing::Recorder<cm_response_t> responses(rig.bus.lcm(), "controller_manager/response");
  rig.cycle(2);
  const std::string huge(60000, 'x');
  const long bytes = lcm_control::testing::output_bytes([&] {
    for (int k = 0; k < 2000; ++k) {
      cm_request_t r = cm_request(cm_request_t::LOAD, {huge});
      r.request_id = k;
      r.client = huge;
      rig.bus.lcm().publish("controller_manager/request", &r);
      command_source_t s{};
      s.request_id = 10000 + k;
      s.client = huge;
      s.controller = huge;
      rig.bus.lcm().publish("controller_manager/command_source", &s);
      rig.pump();
    }
  });
  std::printf("4,000 requests with 60 KB names: %ld bytes of log\n", bytes);
  EXPECT_LT(bytes, 200000);
  EXPECT_EQ(responses.messages.size(), 4000u);
}

// Issue 35, item 2: a LOAD of many unknown names gets one bounded refusal (before: one per name, each listing every
// configured controller: a 129 KB request made a 1.93 MB answer), and a request over kMaxRequestNames is refused at
// once.
TEST(ControllerManagerHostileInput, ManyUnknownNamesGetOneBoundedRefusal) {
  Rig rig;
  cm::Services services(*rig.cm, rig.bus);
  lcm_control::testing::Recorder<cm_response_t> responses(rig.bus.lcm(), "controller_manager/response");
  rig.cycle(2);
  std::vector<std::string> names;
  for (size_t k = 0; k < cm::kMaxRequestNames; ++k) names.push_back("unknown_" + std::to_string(k));
  names.push_back("trajectory");  // a configured one among them is loaded
  names.erase(names.begin());
  cm_request_t r = cm_request(cm_request_t::LOAD, names);
  r.request_id = 1;
  rig.bus.lcm().publish("controller_manager/request", &r);
  names.push_back("one_too_many"), names.push_back("and_another");
  cm_request_t big = cm_request(cm_request_t::LOAD, names);
  big.request_id = 2;
  rig.bus.lcm().publish("controller_manager/request", &big);
  const auto t0 = std::chrono::steady_clock::now();
  rig.pump();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(responses.messages.size(), 2u);
  const cm_response_t& a = responses.messages[0];
  std::printf("a LOAD of %d bytes with %zu unknown names: an answer of %d bytes; both requests served in %.2f ms\n",
              r.getEncodedSize(), names.size() - 3, a.getEncodedSize(), ms);
  EXPECT_FALSE(a.ok);
  EXPECT_LT(a.getEncodedSize(), 64 * 1024);
  EXPECT_NE(a.message.find("loaded 'trajectory'"), std::string::npos) << a.message;
  EXPECT_NE(a.message.find("cannot load 999 controller(s) with no entry in the config"), std::string::npos)
      << a.message.substr(0, 600);
  EXPECT_NE(a.message.find("'unknown_1', 'unknown_2', 'unknown_3', 'unknown_4', 'unknown_5', (and 994 more)"),
            std::string::npos)
      << a.message.substr(0, 600);
  const cm_response_t& b = responses.messages[1];
  EXPECT_FALSE(b.ok);
  EXPECT_NE(b.message.find("malformed request: 1002 names in names[]; at most 1000 in one request"), std::string::npos)
      << b.message;
}
