// The LCM request/response layer in-process: answers carry the request id and
// the controllers; requests that arrive during a switch wait for it, in order.
#include "controller_manager/services.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "bus/messages.hpp"
#include "lcm_control/run_config_t.hpp"
#include "test/controller_manager/rig.hpp"
#include "test/support/lcm_test.hpp"
#include "controllers/builtin.hpp"

using namespace lcm_control;
using namespace lcm_control::cm;
using lcm_control::testing::Recorder;
using lcm_control::testing::Rig;

namespace {
cm_request_t request(int64_t id, int8_t op, std::vector<std::string> names = {}, std::vector<std::string> start = {},
                     std::vector<std::string> stop = {}) {
  cm_request_t r = cm_request(op, std::move(names), std::move(start), std::move(stop));
  r.request_id = id;
  return r;
}
}  // namespace

TEST(ControllerManagerServices, RequestsDuringASwitchWaitForItInOrder) {
  Rig rig;
  Services services(*rig.cm, rig.bus);
  Recorder<cm_response_t> responses(rig.bus.lcm(), "controller_manager/response");
  rig.cycle(2);  // hardware ticking: switches wait for the next cycle
  rig.publish("controller_manager/request", request(1, cm_request_t::LOAD, {"slide_position", "tilt_position"}));
  rig.publish("controller_manager/request", request(2, cm_request_t::SWITCH, {}, {"slide_position"}));
  rig.publish("controller_manager/request", request(3, cm_request_t::UNLOAD, {"slide_position"}));
  rig.publish("controller_manager/request", request(4, cm_request_t::LIST));
  ASSERT_EQ(responses.messages.size(), 1u);  // 2 waits for a cycle, 3 and 4 wait for 2
  rig.cycle(1);
  ASSERT_EQ(responses.messages.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(responses.messages[k].request_id, k + 1);
  EXPECT_TRUE(responses.messages[1].ok) << responses.messages[1].message;
  EXPECT_FALSE(responses.messages[2].ok);  // slide_position is running by then
  EXPECT_NE(responses.messages[2].message.find("it is running"), std::string::npos);
  const auto& list = responses.messages[3];
  ASSERT_EQ(list.num_controllers, 2);
  EXPECT_EQ(list.controllers[0].state, "running");
  EXPECT_EQ(list.controllers[1].state, "initialized");
}

TEST(ControllerManagerServices, ListTypesAndEmptyNames) {
  Rig rig;
  Services services(*rig.cm, rig.bus);
  Recorder<cm_response_t> responses(rig.bus.lcm(), "controller_manager/response");
  rig.publish("controller_manager/request", request(7, cm_request_t::LIST_TYPES));
  rig.publish("controller_manager/request", request(8, cm_request_t::SWITCH, {}, {""}));
  ASSERT_EQ(responses.messages.size(), 2u);
  EXPECT_EQ(responses.messages[0].num_types, 37);
  EXPECT_FALSE(responses.messages[1].ok);
  EXPECT_EQ(responses.messages[1].message, "malformed request: start[0] is an empty name");
}

// CONFIG: the run's configuration on controller_manager/config, the files' texts as read, for a recording to replay.
TEST(ControllerManagerServices, ConfigPublishesWhatTheRunWasStartedWith) {
  Rig rig;
  Services services(*rig.cm, rig.bus);
  Recorder<cm_response_t> responses(rig.bus.lcm(), "controller_manager/response");
  Recorder<run_config_t> configs(rig.bus.lcm(), "controller_manager/config");
  rig.publish("controller_manager/request", request(9, cm_request_t::CONFIG));
  ASSERT_EQ(responses.messages.size(), 1u);
  EXPECT_TRUE(responses.messages[0].ok) << responses.messages[0].message;
  EXPECT_NE(responses.messages[0].message.find("published the run's configuration on controller_manager/config"),
            std::string::npos)
      << responses.messages[0].message;
  ASSERT_EQ(configs.messages.size(), 1u);
  const run_config_t& c = configs.messages[0];
  auto text = [](const std::string& path) {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  EXPECT_EQ(c.urdf_path, lcm_control::testing::data("test_bot.urdf"));
  EXPECT_EQ(c.urdf, text(c.urdf_path));
  ASSERT_EQ(c.num_configs, 1);
  EXPECT_EQ(c.config_paths[0], lcm_control::testing::data("test_bot.yaml"));
  EXPECT_EQ(c.configs[0], text(c.config_paths[0]));
  EXPECT_FALSE(c.version.empty());
  EXPECT_EQ(c.process, "controller_manager");
  EXPECT_EQ(c.num_argv, 0) << "the rig was given no command line";
}

// SIGINT while a switch is pending and another waits for it: every request gets a refusal, and nothing is left
// pending that points at the Services (main destroys them before the manager: this was a double free).
TEST(ControllerManagerServices, ShutdownAnswersThePendingAndTheWaitingSwitchAndLeavesNothingPending) {
  Rig rig;
  auto services = std::make_unique<Services>(*rig.cm, rig.bus);
  Recorder<cm_response_t> responses(rig.bus.lcm(), "controller_manager/response");
  rig.cycle(2);
  rig.publish("controller_manager/request", request(1, cm_request_t::LOAD, {"slide_position", "tilt_position"}));
  rig.publish("controller_manager/request", request(2, cm_request_t::SWITCH, {}, {"slide_position"}));
  rig.publish("controller_manager/request", request(3, cm_request_t::SWITCH, {}, {"tilt_position"}));
  ASSERT_TRUE(rig.cm->busy());
  rig.cm->shutdown();
  EXPECT_FALSE(rig.cm->busy());
  services.reset();
  rig.pump();
  ASSERT_EQ(responses.messages.size(), 3u);
  for (int k = 1; k < 3; ++k) {
    EXPECT_EQ(responses.messages[k].request_id, k + 1);
    EXPECT_FALSE(responses.messages[k].ok);
    EXPECT_NE(responses.messages[k].message.find("shutting down"), std::string::npos) << responses.messages[k].message;
  }
  rig.cm.reset();  // the manager's destructor shuts down again: no answer to give, nothing to call
}

// Served in slices (as the controller_manager program does): a LOAD of several names takes several serve() calls, the
// answers keep the requests' order, a request waits for a switch in progress, and a reload reads its YAML on a worker
// thread while the loop goes on cycling.
TEST(ControllerManagerServices, InSlicesABatchSpansSeveralServesAndAnswersKeepTheirOrder) {
  Rig rig;
  ManagerOptions options;
  options.slice_us = 1;  // one name, one answer or one destruction at a time
  rig.cm.reset();
  rig.cm = std::make_unique<ControllerManager>(rig.model, rig.bus, builtin_registry(), options);
  Services services(*rig.cm, rig.bus, options.slice_us);
  Recorder<cm_response_t> responses(rig.bus.lcm(), "controller_manager/response");
  auto serve = [&] {
    services.serve(monotonic_us() + options.slice_us);
    rig.pump();
  };
  rig.cycle(2);
  rig.publish("controller_manager/request",
              request(1, cm_request_t::LOAD, {"slide_position", "tilt_position", "wheel_velocity"}));
  rig.publish("controller_manager/request", request(2, cm_request_t::LIST));
  EXPECT_TRUE(responses.messages.empty());  // queued, not served by the handler
  int serves = 0;
  while (responses.messages.empty() && serves < 100) serve(), ++serves;
  EXPECT_GE(serves, 3);
  ASSERT_EQ(responses.messages.size(), 1u);
  serve();
  ASSERT_EQ(responses.messages.size(), 2u);
  EXPECT_EQ(responses.messages[0].request_id, 1);
  EXPECT_TRUE(responses.messages[0].ok) << responses.messages[0].message;
  EXPECT_EQ(responses.messages[1].request_id, 2);
  EXPECT_EQ(responses.messages[1].num_controllers, 3);

  rig.publish("controller_manager/request", request(3, cm_request_t::SWITCH, {}, {"slide_position"}));
  rig.publish("controller_manager/request", request(4, cm_request_t::UNLOAD, {"slide_position"}));
  for (int k = 0; k < 5; ++k) serve();
  EXPECT_EQ(responses.messages.size(), 2u);  // the switch waits for a cycle, the unload for the switch
  rig.cycle(1);
  for (int k = 0; k < 5; ++k) serve();
  ASSERT_EQ(responses.messages.size(), 4u);
  EXPECT_TRUE(responses.messages[2].ok) << responses.messages[2].message;
  EXPECT_FALSE(responses.messages[3].ok);
  EXPECT_NE(responses.messages[3].message.find("it is running"), std::string::npos) << responses.messages[3].message;

  cm_request_t reload = request(5, cm_request_t::RELOAD);
  reload.force = true;
  rig.publish("controller_manager/request", reload);
  for (const int64_t until = monotonic_us() + 10000000; monotonic_us() < until && responses.messages.size() < 5;) {
    rig.cycle(1);  // the stop, then the YAML read on the worker: the loop keeps cycling meanwhile
    rig.cm->poll(monotonic_us());
    serve();
  }
  ASSERT_EQ(responses.messages.size(), 5u);
  EXPECT_TRUE(responses.messages[4].ok) << responses.messages[4].message;
  EXPECT_TRUE(rig.cm->list().empty());
  for (int k = 0; k < 100 && rig.cm->has_work(); ++k) rig.cm->poll(monotonic_us());
  EXPECT_FALSE(rig.cm->has_work());  // the unloaded controllers destroyed, a few per poll
}
