// The real-time path allocates nothing: a control step (actuators + Bullet) and
// handing commands to the actuators, the sensors, counted through operator new and Bullet's
// allocator hook once the first steps have sized every buffer.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>

#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"
#include "description/load.hpp"

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};

void* counted_malloc(size_t n) {
  if (g_counting) ++g_allocations;
  return std::malloc(n);
}
void counted_free(void* p) { std::free(p); }
}  // namespace

// The replacement pair below is malloc/free on both sides; GCC cannot see that.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t n) {
  if (g_counting) ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace lcm_control::sim {
namespace {

using namespace testing;

long allocations_during(Simulation& sim, int steps, double amplitude) {
  g_allocations = 0;
  g_counting = true;
  run(sim, steps, [&](int k) {
    for (int i = 0; i < sim.actuators().size(); ++i)
      sim.actuators().set_command(i, sim.actuators().wire_mode(i), amplitude * std::sin(k * 0.01 + i));
  });
  g_counting = false;
  return g_allocations;
}

TEST(sim_realtime_path, ControlStepsAllocateNothingOnceWarm) {
  btAlignedAllocSetCustom(counted_malloc, counted_free);
  for (auto model : {turret(), modes_bot()}) {
    Simulation sim(model, {});
    EXPECT_EQ(allocations_during(sim, 3000, 2.0), 0) << model.name;
    sim.actuators().set_e_stop(true);
    EXPECT_EQ(allocations_during(sim, 500, 2.0), 0) << model.name;
    sim.actuators().set_e_stop(false);
    sim.actuators().set_hold_all(true);  // the brakes go back into the world
    EXPECT_EQ(allocations_during(sim, 500, 2.0), 0) << model.name;
    sim.actuators().set_hold_all(false);
    EXPECT_EQ(allocations_during(sim, 500, 2.0), 0) << model.name;
  }
}

TEST(sim_realtime_path, SensorsAllocateNothing) {
  btAlignedAllocSetCustom(counted_malloc, counted_free);
  {
    Simulation sim(load_robot_model(data("ft_pendulum.urdf"), ""), {});  // force-torque and contact
    run(sim, 10, {});
    EXPECT_EQ(allocations_during(sim, 2000, 1.0), 0);
  }
  Simulation box(load_robot_model(data("contact_box.urdf"), ""), {}, {}, WorldOptions{true, true});  // imu, contact
  run(box, 10, {});
  EXPECT_EQ(allocations_during(box, 2000, 0.0), 0);
  ASSERT_FALSE(box.sensors()->empty());
}

TEST(sim_realtime_path, SwitchingCommandInterfacesAllocatesNothing) {
  btAlignedAllocSetCustom(counted_malloc, counted_free);
  Simulation sim(load_robot_model(std::string(LCM_CONTROL_SOURCE_DIR) + "/test/robots/switch_arm.urdf", ""), {});
  Actuators& act = sim.actuators();
  run(sim, 10, {});  // warm
  g_allocations = 0;
  g_counting = true;
  run(sim, 2000, [&](int k) {
    const int8_t mode = (k / 100) % 3 == 0 ? kPos : (k / 100) % 3 == 1 ? kVel : kNone;
    for (int i = 0; i < act.size(); ++i) act.set_command(i, mode, mode == kPos ? 0.3 * std::sin(k * 0.01) : 0.2);
  });
  g_counting = false;
  EXPECT_EQ(g_allocations, 0);
}

TEST(sim_realtime_path, MockHardwareStepsAllocateNothing) {
  const RobotModel m = load_robot_model(std::string(LCM_CONTROL_SOURCE_DIR) + "/test/robots/mock_arm.urdf", "");
  Simulation sim(m, {}, m.initial_positions, {}, Backend::Mock);
  PlayedHardware& hw = sim.hardware();
  g_allocations = 0;
  g_counting = true;
  run(sim, 2000, [&](int k) {
    const int8_t mode = (k / 100) % 3 == 0 ? kPos : (k / 100) % 3 == 1 ? kVel : kNone;
    for (int i = 0; i < hw.size(); ++i) hw.set_command(i, mode, 0.3 * std::sin(k * 0.01));
  });
  g_counting = false;
  EXPECT_EQ(g_allocations, 0);
}

}  // namespace
}  // namespace lcm_control::sim
