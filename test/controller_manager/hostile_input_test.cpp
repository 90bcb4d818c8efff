// Bus input a hostile or broken peer can send the controller manager: forged
// array counts on hardware/state are dropped before decoding and the loop goes
// on answering the real hardware.
#include <gtest/gtest.h>

#include <vector>

#include "test/controller_manager/rig.hpp"

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
