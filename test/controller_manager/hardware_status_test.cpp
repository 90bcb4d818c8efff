// What `cmctl list` says about the hardware: nothing yet, following a session (mode, nominal and measured rate,
// age), e-stop, silence.
#include "controller_manager/hardware_status.hpp"

#include <gtest/gtest.h>

namespace lcm_control::cm {
namespace {

hardware_state_t state(int64_t step, bool lockstep = false) {
  hardware_state_t s{};
  s.session = 0x3fa9c2d1;
  s.step = step;
  s.lockstep = lockstep;
  s.period_us = 1000;
  s.real_time_factor = lockstep ? 18.25 : 1.0;
  return s;
}

TEST(HardwareStatus, NoneYetSaysWhereItWasExpected) {
  HardwareStatus h;
  EXPECT_EQ(h.age_us(5'000'000), -1);
  EXPECT_EQ(h.describe(5'000'000, 250'000, "r1/hardware/state"),
            "no hardware state received on 'r1/hardware/state': is sim_server (or the robot's driver) running with "
            "this namespace and LCM URL? Controllers are not updated until it publishes");
  // A hardware loop of its own (shared memory, or another LCM URL): the flag both programs must agree on.
  EXPECT_EQ(h.describe(5'000'000, 250'000, "hardware/state", "--hardware-url shm:r1"),
            "no hardware state received on 'hardware/state': is sim_server (or the robot's driver) running with "
            "this namespace and --hardware-url shm:r1? Controllers are not updated until it publishes");
}

TEST(HardwareStatus, SessionModeRatesAndAge) {
  HardwareStatus h;
  const int64_t t0 = 1'000'000;
  for (int k = 0; k < 500; ++k) h.seen(state(k), t0 + k * 2000);  // 500 states in 1 s: half the nominal rate
  EXPECT_EQ(h.age_us(t0 + 999'000), 1'000);
  EXPECT_EQ(h.describe(t0 + 999'000, 250'000, "hardware/state"),
            "session 3fa9c2d1, real time, 1000 Hz, step 499, last state 0.001 s ago");
  h.close_window(t0 + 1'000'000);
  EXPECT_EQ(h.describe(t0 + 1'000'000, 250'000, "hardware/state"),
            "session 3fa9c2d1, real time, 1000 Hz (500.0 measured), step 499, last state 0.002 s ago");
  h.seen(state(500, true), t0 + 1'100'000);
  EXPECT_EQ(h.describe(t0 + 1'100'000, 250'000, "hardware/state"),
            "session 3fa9c2d1, lockstep, 1000 Hz (500.0 measured), 18.25x real time, step 500, last state 0.000 s ago");
}

TEST(HardwareStatus, EStopAndSilenceAreSaid) {
  HardwareStatus h;
  hardware_state_t s = state(7);
  s.e_stop = true;
  h.seen(s, 0);
  EXPECT_EQ(h.describe(2'500'000, 250'000, "hardware/state"),
            "session 3fa9c2d1, real time, 1000 Hz, step 7, last state 2.500 s ago; e-stop engaged: the hardware holds "
            "still; SILENT for 2.5 s: controllers are not updated until 'hardware/state' resumes");
  h.close_window(3'000'000);  // a window without states measures 0 Hz
  h.close_window(4'000'000);
  EXPECT_NE(h.describe(4'000'000, 250'000, "hardware/state").find("1000 Hz (0.0 measured)"), std::string::npos);
}

TEST(HardwareStatus, AStepRepeatedLongerThanTheSilenceTimeoutIsSaidToBePaused) {
  HardwareStatus h;
  for (int k = 0; k <= 30; ++k) h.seen(state(42, true), int64_t(k) * 100'000);  // a paused sim_server: 10 Hz, one step
  EXPECT_EQ(h.describe(3'050'000, 250'000, "hardware/state"),
            "session 3fa9c2d1, lockstep, 1000 Hz, 18.25x real time, step 42, last state 0.050 s ago; step 42 repeated "
            "for 3.0 s: the hardware is paused (cmctl resume) or waiting for a command");
  h.seen(state(43, true), 3'100'000);
  EXPECT_EQ(h.describe(3'100'000, 250'000, "hardware/state").find("repeated"), std::string::npos);
}

}  // namespace
}  // namespace lcm_control::cm
