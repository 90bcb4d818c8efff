// Command sources: ticks on hardware time delivered before the update of the
// cycle they are due in (so every step gets its own command), echoes on
// <controller>/command, ends (count, duration, remove, unload), refusals, and
// no allocation on the loop path.
#include "controller_manager/command_sources.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "test/controller_manager/rig.hpp"
#include "controllers/builtin.hpp"

using namespace lcm_control;
using namespace lcm_control::cm;
using lcm_control::testing::Rig;

namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

command_source_t source(const std::string& controller, std::vector<std::string> exprs, double rate = 0,
                        int64_t count = 0, double duration = 0) {
  command_source_t r{};
  r.request_id = 7;
  r.client = "test";
  r.controller = controller;
  r.expressions = std::move(exprs);
  r.num_expressions = int32_t(r.expressions.size());
  r.rate_hz = rate;
  r.count = count;
  r.duration_s = duration;
  return r;
}

template <class Msg>
struct Recorder {
  Recorder(lcm::LCM& lc, const std::string& channel) { lc.subscribe(channel, &Recorder::on, this); }
  void on(const lcm::ReceiveBuffer*, const std::string&, const Msg* m) { messages.push_back(*m); }
  std::vector<Msg> messages;
};

// The command the hardware got for `actuator` at each answered step.
std::vector<double> commanded(const Rig& rig, const std::string& actuator) {
  size_t a = 0;
  while (a < rig.act.size() && rig.act[a].name != actuator) ++a;
  std::vector<double> v;
  for (const auto& c : rig.commands) v.push_back(c.command[a]);
  return v;
}

}  // namespace

TEST(CommandSources, EveryStepGetsItsOwnCommandBeforeTheUpdate) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);  // at once: no hardware yet
  Recorder<float64_t> echo(rig.bus.lcm(), "slide_position/command");
  const Reply r = rig.cm->command_sources().handle(source("slide_position", {"0.001*(i+1) + t"}, 0, 50));
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(has(r.message, "every control step")) << r.message;
  rig.cycle(60);
  const auto v = commanded(rig, "slide_motor");
  ASSERT_GE(v.size(), 60u);
  for (int k = 0; k < 50; ++k) EXPECT_NEAR(v[k], 0.001 * (k + 1) + k * 1e-3, 1e-12) << "step " << k;
  for (int k = 50; k < 60; ++k) EXPECT_NEAR(v[k], 0.05 + 0.049, 1e-12) << "holds the last one";
  ASSERT_EQ(echo.messages.size(), 50u);
  for (int k = 0; k < 50; ++k) {
    EXPECT_EQ(echo.messages[k].utime, rig.commands[k].utime);
    EXPECT_DOUBLE_EQ(echo.messages[k].data, v[k]);
  }
  EXPECT_EQ(rig.cm->command_sources().active(), 0u);
}

TEST(CommandSources, RateTicksOnHardwareTimeAndEndsAfterDuration) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);
  rig.cycle(3);  // ticking: the source starts at the next cycle
  const int64_t start_us = rig.step * 1000;
  Recorder<float64_t> echo(rig.bus.lcm(), "slide_position/command");
  Recorder<cm_response_t> answers(rig.bus.lcm(), "controller_manager/response");
  ASSERT_TRUE(rig.cm->command_sources().handle(source("slide_position", {"i"}, 60, 0, 0.1)).ok);
  rig.cycle(200);
  rig.cm->poll(monotonic_us());
  rig.pump();
  // ticks 0..5 (t = j/60 < 0.1), due at start + j/60 s, used from the first step at or after that
  ASSERT_EQ(echo.messages.size(), 6u);
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(echo.messages[j].utime, start_us + std::llround(j * 1e6 / 60)) << j;
    EXPECT_EQ(echo.messages[j].data, j);
  }
  const auto v = commanded(rig, "slide_motor");
  const size_t first = 3;
  for (size_t k = first; k < first + 100; ++k) {
    const int64_t us = int64_t(k - first) * 1000;
    EXPECT_EQ(v[k], std::min<int64_t>(5, us * 60 / 1000000)) << "step " << k;
  }
  ASSERT_EQ(answers.messages.size(), 1u);
  EXPECT_EQ(answers.messages[0].request_id, 7);
  EXPECT_EQ(answers.messages[0].op, cm_response_t::OP_COMMAND_SOURCE);
  EXPECT_TRUE(has(answers.messages[0].message, "ended (duration reached) after 6 tick(s)"))
      << answers.messages[0].message;
}

TEST(CommandSources, StartsWithTheFirstHardwareStateAfterARestart) {
  Rig rig;
  ASSERT_TRUE(rig.load("pos_group").ok);
  ASSERT_TRUE(rig.switch_({"pos_group"}, {}).ok);
  ASSERT_TRUE(rig.cm->command_sources().handle(source("pos_group", {"i", "-i"}, 0, 3)).ok);
  rig.step = 1000;  // the first state: controllers restart from it, tick 0 is its step
  rig.cycle(4);
  const auto a = commanded(rig, "slide_motor"), b = commanded(rig, "tilt_motor");
  ASSERT_EQ(a.size(), 4u);
  EXPECT_EQ(a, (std::vector<double>{0, 1, 2, 2}));
  EXPECT_EQ(b, (std::vector<double>{0, -1, -2, -2}));
}

TEST(CommandSources, RemoveUnloadAndReplaceEndTheSource) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);
  auto& cs = rig.cm->command_sources();
  ASSERT_TRUE(cs.handle(source("slide_position", {"1"})).ok);
  const Reply replaced = cs.handle(source("slide_position", {"2"}));
  EXPECT_TRUE(has(replaced.message, "replaced the previous one")) << replaced.message;
  rig.cycle(2);
  EXPECT_EQ(commanded(rig, "slide_motor").back(), 2);
  EXPECT_EQ(cs.active(), 1u);
  command_source_t rm{};
  rm.controller = "slide_position";
  rm.remove = true;
  const Reply removed = cs.handle(rm);
  EXPECT_TRUE(removed.ok) << removed.message;
  EXPECT_EQ(cs.active(), 0u);
  EXPECT_FALSE(cs.handle(rm).ok);
  ASSERT_TRUE(cs.handle(source("slide_position", {"3"})).ok);
  ASSERT_TRUE(rig.switch_({}, {"slide_position"}).ok);
  ASSERT_TRUE(rig.cm->unload("slide_position").ok);
  EXPECT_EQ(cs.active(), 0u);
  rig.cycle(2);
  rig.cm->poll(monotonic_us());
}

TEST(CommandSources, RefusalsNameTheProblem) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.load("pos_group").ok);
  ASSERT_TRUE(rig.load("joint_state_controller").ok);
  auto& cs = rig.cm->command_sources();
  auto why = [&](const command_source_t& r) {
    const Reply reply = cs.handle(r);
    EXPECT_FALSE(reply.ok);
    return reply.message;
  };
  EXPECT_TRUE(has(why(source("nope", {"1"})), "it is not loaded (loaded: slide_position, pos_group")) << why(source("nope", {"1"}));
  EXPECT_TRUE(has(why(source("slide_position", {"1", "2"})), "takes one value"));
  EXPECT_TRUE(has(why(source("pos_group", {"1"})), "1 expression(s) for 2 joints"));
  EXPECT_TRUE(has(why(source("joint_state_controller", {"1"})), "takes no float64_t"));
  EXPECT_TRUE(has(why(source("slide_position", {"sin("})), "expression 'sin('"));
  EXPECT_TRUE(has(why(source("slide_position", {"1"}, -1)), "rate_hz"));
  EXPECT_EQ(cs.active(), 0u);
}

TEST(CommandSources, NotFiniteEndsTheSourceAndNothingIsDelivered) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);
  Recorder<cm_response_t> answers(rig.bus.lcm(), "controller_manager/response");
  ASSERT_TRUE(rig.cm->command_sources().handle(source("slide_position", {"sqrt(2-i)"})).ok);
  rig.cycle(6);
  rig.cm->poll(monotonic_us());
  rig.pump();
  const auto v = commanded(rig, "slide_motor");
  EXPECT_DOUBLE_EQ(v[5], 0.0);
  EXPECT_DOUBLE_EQ(v[2], 0.0);
  EXPECT_DOUBLE_EQ(v[1], 1.0);
  ASSERT_EQ(answers.messages.size(), 1u);
  EXPECT_FALSE(answers.messages[0].ok);
  EXPECT_TRUE(has(answers.messages[0].message, "nan at i=3 t=0.003")) << answers.messages[0].message;
}

TEST(CommandSources, OverLcmAndWithoutAllocationOnTheLoopPath) {
  Rig rig;
  ASSERT_TRUE(rig.load("wheel_velocity").ok);
  ASSERT_TRUE(rig.load("pos_group").ok);
  ASSERT_TRUE(rig.switch_({"wheel_velocity", "pos_group"}, {}).ok);
  Recorder<cm_response_t> answers(rig.bus.lcm(), "controller_manager/response");
  rig.publish("controller_manager/command_source", source("wheel_velocity", {"3.14*sin(i/100)"}, 60));
  command_source_t g = source("pos_group", {"sin(t)", "cos(t)"});
  g.request_id = 8;
  rig.publish("controller_manager/command_source", g);
  ASSERT_EQ(answers.messages.size(), 2u);
  EXPECT_TRUE(answers.messages[0].ok) << answers.messages[0].message;
  EXPECT_EQ(answers.messages[1].request_id, 8);
  rig.cycle(50);  // warm-up
  EXPECT_EQ(rig.allocations_in_cycles(500, false, true), 0);
  EXPECT_EQ(rig.cm->command_sources().ticks("pos_group"), 550);
}

// A client whose answer was lost sends the request again under the same request_id: it gets the same answer, and
// the source is registered once (its ticks go on rather than starting again).
TEST(CommandSources, ARequestSentAgainIsAnsweredAgainAndRegisteredOnce) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);
  Recorder<cm_response_t> answers(rig.bus.lcm(), "controller_manager/response");
  const command_source_t req = source("slide_position", {"i"});
  rig.publish("controller_manager/command_source", req);
  rig.cycle(5);
  const int64_t ticks = rig.cm->command_sources().ticks("slide_position");
  rig.publish("controller_manager/command_source", req);
  rig.cycle(5);
  ASSERT_EQ(answers.messages.size(), 2u);
  EXPECT_EQ(answers.messages[1].request_id, req.request_id);
  EXPECT_EQ(answers.messages[1].utime, answers.messages[0].utime);
  EXPECT_EQ(answers.messages[1].message, answers.messages[0].message);
  EXPECT_FALSE(has(answers.messages[1].message, "replaced")) << answers.messages[1].message;
  EXPECT_EQ(rig.cm->command_sources().ticks("slide_position"), ticks + 5);
  const auto v = commanded(rig, "slide_motor");
  EXPECT_DOUBLE_EQ(v.back(), double(ticks + 4));

  command_source_t other = req;  // a new request_id is a new registration
  other.request_id = 8;
  rig.publish("controller_manager/command_source", other);
  ASSERT_EQ(answers.messages.size(), 3u);
  EXPECT_TRUE(has(answers.messages[2].message, "replaced")) << answers.messages[2].message;
}

// The source publishes each tick on <controller>/command after the cycle, and the controller manager receives its
// own message back from the bus. That echo comes on the shared bus while the cycles come on the hardware loop's
// socket, so under load it can arrive after the next tick: it must not put the older value back (in lockstep that
// made one run of three differ from the others). Other messages on the channel are ignored while the source owns
// it, counted in its end; once it has ended the channel is the bus's again.
TEST(CommandSources, ALateEchoOrAnotherPublisherCannotOverrideTheSource) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);
  rig.cycle(2);
  Recorder<float64_t> echo(rig.bus.lcm(), "slide_position/command");
  Recorder<cm_response_t> answers(rig.bus.lcm(), "controller_manager/response");
  ASSERT_TRUE(rig.cm->command_sources().handle(source("slide_position", {"10 + i"}, 100, 4)).ok);
  rig.cycle(25);  // ticks 0, 1 and 2 (every 10 steps)
  ASSERT_EQ(echo.messages.size(), 3u);
  EXPECT_EQ(commanded(rig, "slide_motor").back(), 12);

  // Tick 0 again, as a late echo would bring it (memq:// delivered the real echo at once, so this copy counts as
  // another publisher's below; the four real echoes count as nothing).
  rig.publish("slide_position/command", echo.messages[0]);
  rig.cycle();
  EXPECT_EQ(commanded(rig, "slide_motor").back(), 12) << "a late echo put tick 0 back";

  float64_t other{};
  other.utime = 123;
  other.data = 42;
  rig.publish("slide_position/command", other);
  rig.publish("slide_position/command", other);
  rig.cycle();
  EXPECT_EQ(commanded(rig, "slide_motor").back(), 12) << "another publisher took over a running source";

  rig.cycle(10);  // tick 3, then the count ends it
  EXPECT_EQ(commanded(rig, "slide_motor").back(), 13);
  rig.cm->poll(monotonic_us());
  rig.pump();
  ASSERT_EQ(answers.messages.size(), 1u);
  EXPECT_TRUE(has(answers.messages[0].message, "ended (count reached) after 4 tick(s)")) << answers.messages[0].message;
  EXPECT_TRUE(has(answers.messages[0].message, "3 message(s) from the bus on 'slide_position/command' were ignored"))
      << answers.messages[0].message;

  rig.publish("slide_position/command", other);  // the channel is the bus's again
  rig.cycle();
  EXPECT_EQ(commanded(rig, "slide_motor").back(), 42);
}

// A source that has ended but not yet been answered (poll() has not run) must not give the channel back from under
// the source registered after it.
TEST(CommandSources, ANewSourceKeepsTheChannelWhenTheOneBeforeItIsAnswered) {
  Rig rig;
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);
  ASSERT_TRUE(rig.cm->command_sources().handle(source("slide_position", {"1"}, 0, 1)).ok);
  rig.cycle(2);  // ended (count reached), not yet answered
  command_source_t next = source("slide_position", {"5"}, 100);  // a tick every 10 steps
  next.request_id = 8;
  ASSERT_TRUE(rig.cm->command_sources().handle(next).ok);
  rig.cm->poll(monotonic_us());  // answers the first
  rig.cycle(2);
  float64_t other{};
  other.utime = 123;
  other.data = 42;
  rig.publish("slide_position/command", other);
  rig.cycle();
  EXPECT_EQ(commanded(rig, "slide_motor").back(), 5) << "the second source lost its channel";
}

namespace {

// A controller type the manager has never heard of: it declares its numbers with take_commands and commands twice
// what it gets. Nothing in the manager or the command sources names it.
class Doubler : public Controller {
 public:
  void init(ControllerContext& ctx) override {
    joint_ = ctx.claim(ctx.params().string("joint"), Interface::Position);
    ctx.take_commands(false, 1, [this](const double* v) { value_ = 2 * v[0]; });
  }
  void starting(const Time&) override {}
  void update(const Time&, double) override { joint_->command = value_; }

 private:
  JointData* joint_ = nullptr;
  double value_ = 0;
};

}  // namespace

TEST(CommandSources, ANewControllerTypeIsOneRegistrationAndTakesSourcesThroughItsCommandInput) {
  Registry registry;
  register_builtin(registry);
  registry.add("position_controllers/JointPositionController", [](const std::string&) { return std::make_unique<Doubler>(); });
  Rig rig(registry);
  ASSERT_TRUE(rig.load("slide_position").ok);
  ASSERT_TRUE(rig.switch_({"slide_position"}, {}).ok);
  ASSERT_TRUE(rig.cm->command_sources().handle(source("slide_position", {"0.01*(i+1)"}, 0, 10)).ok);
  rig.cycle(12);
  rig.cm->poll(monotonic_us());  // the source ends and gives the channel back
  rig.pump();
  EXPECT_EQ(rig.cm->command_sources().active(), 0u);
  auto v = commanded(rig, "slide_motor");
  for (int k = 0; k < 10; ++k) EXPECT_NEAR(v[k], 0.02 * (k + 1), 1e-12) << "step " << k;
  float64_t m{};
  m.data = 0.25;
  rig.bus.lcm().publish("slide_position/command", &m);  // and from the bus, through the same input
  rig.pump();
  rig.cycle(2);
  v = commanded(rig, "slide_motor");
  EXPECT_DOUBLE_EQ(v.back(), 0.5);
  m.data = NAN;
  rig.bus.lcm().publish("slide_position/command", &m);
  rig.pump();
  rig.cycle(2);
  EXPECT_DOUBLE_EQ(commanded(rig, "slide_motor").back(), 0.5);
  int64_t dropped = -1;
  for (const auto& slot : rig.cm->loop().slots())
    if (slot->name == "slide_position") dropped = slot->controller->dropped();
  EXPECT_EQ(dropped, 1);
}
