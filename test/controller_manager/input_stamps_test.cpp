// controller_manager/input_stamps: which messages the manager stamps, and at which cycle (the one after a message was
// taken, or after its result was taken from the intake's thread).
#include <gtest/gtest.h>

#include <vector>

#include "bus/bus.hpp"
#include "bus/digest.hpp"
#include "controller_manager/input_stamps.hpp"
#include "lcm_control/cm_request_t.hpp"

using namespace lcm_control;

namespace {

struct Stamps {
  std::vector<cm_inputs_t> got;
  void on(const lcm::ReceiveBuffer*, const std::string&, const cm_inputs_t* m) { got.push_back(*m); }
};

std::vector<uint8_t> encoded(const cm_request_t& r) {
  std::vector<uint8_t> b(static_cast<size_t>(r.getEncodedSize()));
  r.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

cm_request_t request(int8_t op) {
  cm_request_t r{};
  r.op = op;
  r.client = "test";
  return r;
}

}  // namespace

TEST(InputStamps, EachCycleListsWhatWasTakenSinceTheLastAndADeferredInputWaitsForItsResult) {
  Bus bus("memq://", "r1");
  Stamps stamps;
  bus.lcm().subscribe(bus.channel(channels::kCmInputs), &Stamps::on, &stamps);
  Endpoints endpoints(bus, Endpoints::On::Shared);
  cm::InputStamps inputs(bus, endpoints.publisher<cm_inputs_t>(bus.channel(channels::kCmInputs)));
  auto flush = [&] { while (bus.lcm().handleTimeout(0) > 0) {} };

  const uint8_t command[8] = {1, 2, 3, 4, 5, 6, 7, 8}, goal[5] = {9, 9, 9, 9, 9}, state[3] = {0, 0, 0};
  inputs.taken("r1/hardware/state", state, sizeof state);  // the hardware loop: the cycle itself
  inputs.taken("r1/sim_server/request", state, sizeof state);
  const std::vector<uint8_t> list = encoded(request(cm_request_t::LIST)), load = encoded(request(cm_request_t::LOAD));
  inputs.taken("r1/controller_manager/request", list.data(), list.size());  // a query changes nothing
  inputs.stamp(7, 10);
  flush();
  EXPECT_TRUE(stamps.got.empty()) << "nothing to stamp: no message";

  inputs.taken("r1/arm/command", command, sizeof command);
  inputs.taken("r1/controller_manager/request", load.data(), load.size());
  inputs.taken("r1/arm_trajectory/command", goal, sizeof goal);
  inputs.submitted_off_loop();  // the goal goes to the intake's thread
  inputs.stamp(7, 11);
  flush();
  ASSERT_EQ(stamps.got.size(), 1u);
  const cm_inputs_t& first = stamps.got[0];
  EXPECT_EQ(first.session, 7);
  EXPECT_EQ(first.step, 11);
  EXPECT_EQ(first.channel, (std::vector<std::string>{"r1/arm/command", "r1/controller_manager/request"}));
  EXPECT_EQ(first.digest[0], static_cast<int64_t>(message_digest(command, sizeof command)));
  EXPECT_EQ(first.size, (std::vector<int32_t>{8, static_cast<int32_t>(load.size())}));

  inputs.stamp(7, 12);  // its result not taken yet
  flush();
  EXPECT_EQ(stamps.got.size(), 1u);
  inputs.result_taken();
  inputs.stamp(7, 13);
  flush();
  ASSERT_EQ(stamps.got.size(), 2u);
  EXPECT_EQ(stamps.got[1].step, 13);
  EXPECT_EQ(stamps.got[1].channel, (std::vector<std::string>{"r1/arm_trajectory/command"}));
  EXPECT_EQ(stamps.got[1].size, (std::vector<int32_t>{5}));

  // A job submitted for a message that was not stamped (a hardware message, say) keeps the order of the rest.
  inputs.taken("r1/hardware/state", state, sizeof state);
  inputs.submitted_off_loop();
  inputs.taken("r1/arm_trajectory/command", goal, sizeof goal);
  inputs.submitted_off_loop();
  inputs.result_taken();
  inputs.stamp(7, 14);
  flush();
  EXPECT_EQ(stamps.got.size(), 2u) << "the first result was the unstamped message's";
  inputs.result_taken();
  inputs.stamp(7, 15);
  flush();
  ASSERT_EQ(stamps.got.size(), 3u);
  EXPECT_EQ(stamps.got[2].step, 15);
}
