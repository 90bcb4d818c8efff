// common/bus: where a robot's hardware loop travels (hardware_url_for) and a Bus
// that keeps it apart from the shared bus.
#include <gtest/gtest.h>

#include <regex>
#include <set>

#include "bus/bus.hpp"
#include "lcm_control/float64_t.hpp"
#include "test/support/lcm_test.hpp"

using namespace lcm_control;
namespace lt = lcm_control::testing;

namespace {
int port_of(const std::string& url) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(url, m, std::regex(":([0-9]+)"))) << url;
  return m.empty() ? -1 : std::stoi(m[1]);
}
}  // namespace

TEST(HardwareUrl, EmptyOrSharedIsTheSharedBusAndAUrlIsTakenAsGiven) {
  const std::string shared = "udpm://239.255.76.67:7667?ttl=1";
  EXPECT_EQ(hardware_url_for("", shared, "r0"), shared);
  EXPECT_EQ(hardware_url_for("shared", shared, "r0"), shared);
  EXPECT_EQ(hardware_url_for("udpm://239.255.76.68:9000?ttl=0", shared, "r0"), "udpm://239.255.76.68:9000?ttl=0");
}

TEST(HardwareUrl, AutoKeepsTheGroupAndOptionsAndTakesAPortFromTheNamespace) {
  const std::string shared = "udpm://239.255.76.67:7667?ttl=1&recv_buf_size=4194304";
  const std::string r0 = hardware_url_for("auto", shared, "r0");
  EXPECT_TRUE(std::regex_match(r0, std::regex(R"(udpm://239\.255\.76\.67:[0-9]+\?ttl=1&recv_buf_size=4194304)"))) << r0;
  EXPECT_EQ(hardware_url_for("auto", shared, "/r0/"), r0);  // the namespace as Bus normalises it
  EXPECT_EQ(hardware_url_for("auto", "udpm://239.255.76.67:7667?ttl=1&recv_buf_size=4194304", "r0"), r0);
  std::set<int> ports;
  for (int i = 0; i < 16; ++i) {
    const int p = port_of(hardware_url_for("auto", shared, "r" + std::to_string(i)));
    EXPECT_GE(p, kHardwarePortBase);
    EXPECT_LT(p, kHardwarePortBase + kHardwarePorts);
    ports.insert(p);
  }
  EXPECT_EQ(ports.size(), 16u) << "r0..r15 share a hardware port";
  EXPECT_EQ(hardware_url_for("auto", "udpm://239.255.76.67", ""),
            "udpm://239.255.76.67:" + std::to_string(port_of(hardware_url_for("auto", shared, ""))));
}

TEST(HardwareUrl, AutoOnAUrlThatIsNotUdpmSaysToGiveTheUrl) {
  try {
    hardware_url_for("auto", "memq://", "r0");
    FAIL() << "no error";
  } catch (const BusError& e) {
    EXPECT_NE(std::string(e.what()).find("memq://"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("give the hardware loop's URL"), std::string::npos) << e.what();
  }
}

TEST(HardwareUrl, ABusWithAHardwareUrlKeepsItsLoopOffTheSharedBus) {
  const std::string shared = lt::unique_lcm_url(), hw = lt::unique_lcm_url();
  Bus robot(shared, "r0", hw);
  ASSERT_TRUE(robot.hardware_apart());
  EXPECT_EQ(robot.hardware_url(), hw);
  EXPECT_EQ(robot.fds().size(), 2u);
  lcm::LCM on_shared(shared), on_hw(hw);
  lt::Recorder<float64_t> shared_sees(on_shared, "r0/hardware/state"), hw_sees(on_hw, "r0/hardware/state");
  lt::Recorder<float64_t> shared_sees_js(on_shared, "r0/joint_states");
  float64_t m{};
  m.data = 1;
  robot.hardware().publish(robot.channel(channels::kHardwareState), &m);
  robot.publish(channels::kJointStates, m);
  ASSERT_TRUE(lt::pump_until(on_hw, [&] { return hw_sees.messages.size() == 1; }, 2));
  ASSERT_TRUE(lt::pump_until(on_shared, [&] { return shared_sees_js.messages.size() == 1; }, 2));
  lt::pump_until(on_shared, [] { return false; }, 0.1);
  EXPECT_TRUE(shared_sees.messages.empty());

  // And Bus::handle() delivers from both.
  lt::Recorder<float64_t> robot_hw(robot.hardware(), "r0/hardware/command"), robot_shared(robot.lcm(), "r0/e_stop");
  on_hw.publish("r0/hardware/command", &m);
  on_shared.publish("r0/e_stop", &m);
  for (int i = 0; i < 100 && (robot_hw.messages.empty() || robot_shared.messages.empty()); ++i) robot.handle(20);
  EXPECT_EQ(robot_hw.messages.size(), 1u);
  EXPECT_EQ(robot_shared.messages.size(), 1u);

  Bus one(shared, "r0", "shared");
  EXPECT_FALSE(one.hardware_apart());
  EXPECT_EQ(&one.hardware(), &one.lcm());
  EXPECT_EQ(one.fds().size(), 1u);
}
