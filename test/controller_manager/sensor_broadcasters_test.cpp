// The sensor broadcasters through the real loop (memq:// bus) on hardware that sends sensor values: each publishes
// the hardware's reading in its message at its rate, and a wrong sensor is refused naming the ones there are.
#include <gtest/gtest.h>

#include "lcm_control/imu_t.hpp"
#include "lcm_control/wrench_stamped_t.hpp"
#include "test/controller_manager/rig.hpp"
#include "test/support/lcm_test.hpp"
#include "controllers/builtin.hpp"

using namespace lcm_control;
using lcm_control::testing::Recorder;
using lcm_control::testing::Rig;

namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A rig whose hardware sends the IMU and force-torque values: value k is k + 0.5.
struct SensorRig : Rig {
  SensorRig() : Rig(cm::builtin_registry(), lcm_control::testing::data("sensor_bot.urdf"),
                    lcm_control::testing::data("sensor_bot.yaml")) {
    for (const char* sensor : {"tip_imu", "wrist_ft"})
      for (const std::string& i : sensor_interfaces(std::string(sensor) == "tip_imu" ? SensorKind::Imu
                                                                                      : SensorKind::ForceTorque))
        state.sensor_interface.push_back(std::string(sensor) + "/" + i);
    for (size_t k = 0; k < state.sensor_interface.size(); ++k) state.sensor_value.push_back(double(k) + 0.5);
    state.num_sensor_values = int32_t(state.sensor_value.size());
  }
};

TEST(SensorBroadcasters, Ros2ImuAndForceTorquePublishEveryCycleInTheirMessages) {
  SensorRig rig;
  Recorder<imu_t> imu(rig.bus.lcm(), "imu_broadcaster/imu");
  Recorder<wrench_stamped_t> ft(rig.bus.lcm(), "ft_broadcaster/wrench");
  rig.start("imu_broadcaster");
  rig.start("ft_broadcaster");
  const size_t before = imu.messages.size();
  rig.cycle(100);
  EXPECT_EQ(imu.messages.size() - before, 100u);  // the controller manager's rate
  ASSERT_FALSE(ft.messages.empty());
  const imu_t& m = imu.messages.back();
  EXPECT_EQ(m.frame_id, "tip_imu_link");
  EXPECT_EQ(m.orientation.x, 0.5);
  EXPECT_EQ(m.orientation.w, 3.5);
  EXPECT_EQ(m.angular_velocity.z, 6.5);
  EXPECT_EQ(m.linear_acceleration.z, 9.5);
  EXPECT_EQ(m.utime, rig.state.utime);
  const wrench_stamped_t& w = ft.messages.back();
  EXPECT_EQ(w.frame_id, "tool");
  EXPECT_EQ(w.force.x, 10.5);  // after the IMU's ten values
  EXPECT_EQ(w.torque.z, 15.5);
}

TEST(SensorBroadcasters, Ros1ControllersPublishEachSensorOnItsNameAtPublishRate) {
  SensorRig rig;
  Recorder<imu_t> imu(rig.bus.lcm(), "tip_imu");
  Recorder<wrench_stamped_t> ft(rig.bus.lcm(), "wrist_ft");
  rig.start("imu_ros1");
  rig.start("ft_ros1");
  rig.cycle(1000);
  EXPECT_NEAR(double(imu.messages.size()), 100, 1);
  EXPECT_NEAR(double(ft.messages.size()), 50, 1);
  ASSERT_FALSE(imu.messages.empty());
  EXPECT_EQ(imu.messages.back().frame_id, "tip_imu_frame");  // the plugin's <frameName>
  EXPECT_EQ(ft.messages.back().frame_id, "tool");             // the joint's child link
}

TEST(SensorBroadcasters, HardwareWithoutTheSensorPublishesNothing) {
  SensorRig rig;
  rig.state.sensor_interface.clear();
  rig.state.sensor_value.clear();
  rig.state.num_sensor_values = 0;
  Recorder<imu_t> imu(rig.bus.lcm(), "imu_broadcaster/imu");
  rig.start("imu_broadcaster");
  rig.cycle(10);
  EXPECT_TRUE(imu.messages.empty());
  EXPECT_EQ(rig.cm->hardware().missing_sensors(), (std::vector<std::string>{"tip_imu", "wrist_ft"}));
}

TEST(SensorBroadcasters, AWrongSensorIsRefusedNamingTheOnesThereAre) {
  SensorRig rig;
  const cm::Reply kind = rig.load("imu_wrong_kind");
  EXPECT_FALSE(kind.ok);
  EXPECT_TRUE(has(kind.message, "sensor_name: sensor 'wrist_ft' is force_torque, not imu (imu sensors: tip_imu)"))
      << kind.message;
  const cm::Reply unknown = rig.load("imu_unknown");
  EXPECT_FALSE(unknown.ok);
  EXPECT_TRUE(has(unknown.message, "declares no sensor 'tip_imuu' (imu sensors: tip_imu)")) << unknown.message;
  const cm::Reply mixed = rig.load("ft_mixed");
  EXPECT_FALSE(mixed.ok);
  EXPECT_TRUE(has(mixed.message, "'other/torque.x' is of sensor 'other' while the others are of 'wrist_ft'"))
      << mixed.message;
}

}  // namespace
