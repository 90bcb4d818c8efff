// Bus input a hostile or broken peer can send the controller manager: forged
// array counts on hardware/state are dropped before decoding and the loop goes
// on answering the real hardware.
#include <gtest/gtest.h>

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
