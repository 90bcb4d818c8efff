// In-process fuzz of every channel the two servers and the tools subscribe (issue 18): the
// real controller manager (test_bot, every configured controller loaded, as
// many running as their claims allow) and the real sim_server I/O around a
// Bullet turret_bot, on LCM's in-process memq:// bus, take 10,000 seeded
// hostile payloads per channel between genuine control cycles. Nothing may
// throw, hang, put a non-finite number on hardware/command, joint_states or
// hardware/state, or stop the loop; the log must stay small.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>

#include "bus/messages.hpp"
#include "controller_manager/services.hpp"
#include "lcm_control/pid_gains_t.hpp"
#include "lcm_control/sim_clock_t.hpp"
#include "lcm_control/visit.hpp"
#include "sim_server/sim_io.hpp"
#include "sim_server/simulation.hpp"
#include "test/controller_manager/rig.hpp"
#include "test/reliability/fuzz/payloads.hpp"
#include "test/support/lcm_test.hpp"
#include "tools/lib/messages/fields.hpp"
#include "tools/lib/messages/message_text.hpp"
#include "tools/lib/clients/time_base.hpp"
#include "description/load.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control;

namespace {

int payloads_per_channel() {
  const char* v = std::getenv("LCM_CONTROL_FUZZ_PAYLOADS");
  return v && *v ? std::atoi(v) : 10000;
}


bool finite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

struct Tally {
  std::string channel;
  int64_t tried = 0, crashes = 0, hangs = 0;
  double worst_ms = 0;
  long log_bytes = 0;
  double seconds = 0;
  void print(const char* suite_note) const {
    std::printf("RELIABILITY|fuzz|%s|tried=%lld|ok=%lld|crashes=%lld|hangs=%lld|%s; slowest %.2f ms; log %ld B in %.2f s\n",
                channel.c_str(), static_cast<long long>(tried), static_cast<long long>(tried - crashes - hangs),
                static_cast<long long>(crashes), static_cast<long long>(hangs), suite_note, worst_ms, log_bytes,
                seconds);
  }
};

// Sends n payloads from `make` on `channel`, calling deliver() after each and between() every 10th.
Tally flood(lcm::LCM& lc, const std::string& channel, int n, const std::function<std::vector<uint8_t>()>& make,
            const std::function<void()>& deliver, const std::function<void()>& between) {
  Tally t;
  t.channel = channel;
  const auto start = std::chrono::steady_clock::now();
  t.log_bytes = lt::output_bytes([&] {
    for (int k = 0; k < n; ++k) {
      const std::vector<uint8_t> b = make();
      lc.publish(channel, b.data(), unsigned(b.size()));
      const auto t0 = std::chrono::steady_clock::now();
      try {
        deliver();
      } catch (...) {
        ++t.crashes;
      }
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      t.worst_ms = std::max(t.worst_ms, ms);
      if (ms > 1000) {
        ++t.hangs;
        std::fprintf(stderr, "FUZZ HANG: %s payload %d took %.0f ms (%zu bytes)\n", channel.c_str(), k, ms, b.size());
        const std::string path = "/tmp/fuzz_hang_" + std::to_string(k) + ".bin";
        if (FILE* f = std::fopen(path.c_str(), "wb")) {
          std::fwrite(b.data(), 1, b.size(), f);
          std::fclose(f);
        }
      }
      ++t.tried;
      if (k % 10 == 9) between();
    }
  });
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

// The type a controller manager channel takes.
std::string expected_type(const std::string& channel, const std::string& controller_type) {
  if (channel == "hardware/state") return "hardware_state_t";
  if (channel == "controller_manager/request") return "cm_request_t";
  if (channel == "controller_manager/command_source") return "command_source_t";
  if (channel.size() > 10 && channel.compare(channel.size() - 10, 10, "/gains/set") == 0) return "pid_gains_t";
  if (controller_type.find("Trajectory") != std::string::npos) return "joint_trajectory_t";
  if (controller_type.find("Group") != std::string::npos) return "float64_array_t";
  return "float64_t";
}

std::vector<uint8_t> payload_of(lt::Payloads& p, const std::string& type, const lt::Hints& h) {
  std::vector<uint8_t> out;
  for_each_type([&](auto tag) {
    using Msg = typename decltype(tag)::type;
    if (out.empty() && type == Msg::getTypeName()) out = p.next<Msg>(h);
  });
  return out;
}

}  // namespace

TEST(Fuzz, ControllerManagerTakesHostilePayloadsOnEveryChannel) {
  const int n = payloads_per_channel();
  lt::Rig rig;
  cm::Services services(*rig.cm, rig.bus);
  lt::Recorder<hardware_command_t> commands(rig.bus.lcm(), "hardware/command");
  lt::Recorder<joint_state_t> joint_states(rig.bus.lcm(), "joint_states");
  rig.cycle(2);
  for (const auto& spec : rig.model.controllers) rig.load(spec.name);
  for (const auto& s : rig.cm->loop().slots()) rig.switch_({s->name}, {}, 1);  // best effort: claims decide
  std::vector<std::pair<std::string, std::string>> channels{{"hardware/state", ""},
                                                            {"controller_manager/request", ""},
                                                            {"controller_manager/command_source", ""}};
  int running = 0;
  lt::Hints hints;
  for (const auto& s : rig.cm->loop().slots()) {
    running += s->running;
    hints.names.push_back(s->name);
    for (const auto& c : s->endpoints->channels()) channels.emplace_back(c, s->type);
  }
  for (const auto& j : rig.cm->hardware().joints()) {
    hints.names.push_back(j.name);
    hints.names.push_back(j.actuator);
  }
  std::printf("%zu controllers loaded, %d running, %zu channels\n", rig.cm->loop().slots().size(), running,
              channels.size());
  ASSERT_GT(running, 5);

  lt::Payloads payloads(20261123);
  int64_t total = 0;
  for (const auto& [channel, controller_type] : channels) {
    const std::string type = expected_type(channel, controller_type);
    const size_t answered = rig.commands.size();
    Tally t = flood(
        rig.bus.lcm(), channel, n,
        [&] {
          hints.integers = {rig.session, rig.step, rig.step - 1};
          return payload_of(payloads, type, hints);
        },
        [&] { rig.pump(); }, [&] { rig.cycle(1); });
    t.channel = "controller_manager " + channel + " (" + type + ")";
    t.print("in-process, 1 control cycle per 10 payloads");
    total += t.tried;
    EXPECT_EQ(t.crashes, 0) << channel;
    EXPECT_EQ(t.hangs, 0) << channel;
    EXPECT_LT(double(t.log_bytes), 16384 * (t.seconds + 1)) << channel << ": the log grows with the flood";
    // The loop still answers the real hardware after the flood.
    const size_t before = rig.commands.size();
    rig.cycle(5);
    EXPECT_GE(rig.commands.size(), before + 4) << channel << ": the loop stopped answering";
    EXPECT_GT(rig.commands.size(), answered) << channel;
  }
  rig.pump();
  int64_t bad_commands = 0, bad_states = 0;
  for (const auto& c : commands.messages)
    for (int k = 0; k < c.num_actuators && k < int(c.command.size()); ++k)
      if (c.mode[size_t(k)] != hardware_command_t::MODE_NONE && !std::isfinite(c.command[size_t(k)])) ++bad_commands;
  for (const auto& js : joint_states.messages)
    if (!finite(js.position) || !finite(js.velocity) || !finite(js.effort)) ++bad_states;
  std::printf("%lld payloads; %zu hardware/command (%lld non-finite), %zu joint_states (%lld non-finite)\n",
              static_cast<long long>(total), commands.messages.size(), static_cast<long long>(bad_commands),
              joint_states.messages.size(), static_cast<long long>(bad_states));
  EXPECT_EQ(bad_commands, 0);
  EXPECT_EQ(bad_states, 0);
}

TEST(Fuzz, SimServerTakesHostilePayloadsOnEveryChannel) {
  const int n = payloads_per_channel();
  const RobotModel model = load_robot_model(lt::source("config/turret_bot.urdf"), lt::source("config/turret_bot.yaml"));
  Bus bus("memq://", "");
  sim::Simulation sim(model, {});
  sim::SimIo io(bus, sim, true);
  lt::Recorder<hardware_state_t> states(bus.lcm(), "hardware/state");
  lt::Hints hints;
  for (const auto& t : model.transmissions) {
    hints.names.push_back(t.joint);
    hints.names.push_back(t.actuator);
  }
  // The actuators as sim_server names them, from its first state.
  io.publish_state(1.0);
  bus.lcm().handleTimeout(0);
  ASSERT_EQ(states.messages.size(), 1u);
  const hardware_state_t first = states.messages[0];
  // One genuine lockstep cycle: state k, a command tagged k (j1 to 0.5, j2 to -0.3), step.
  hardware_command_t genuine{};
  resize(genuine, first.num_actuators);
  genuine.name = first.name;
  genuine.mode = first.mode;
  genuine.command.assign(size_t(first.num_actuators), -0.3);
  genuine.command[0] = 0.5;
  auto cycle = [&] {
    io.publish_state(1.0);
    io.expect_step(sim.step_count());
    genuine.utime = sim.time_us();
    genuine.step = sim.step_count();
    genuine.session = io.session();
    bus.lcm().publish("hardware/command", &genuine);
    io.poll_until(monotonic_us());
    io.take_command();
    sim.step();
  };
  cycle();
  cycle();
  // The gains in force, to restore after the flood: a well-formed hostile pid_gains_t may legitimately change them.
  lt::Recorder<pid_gains_t> gains(bus.lcm(), "sim_server/gains");
  for (const char* joint : {"j1", "j2"}) {
    pid_gains_t q{};
    q.owner = "sim_server";
    q.joint = joint;
    q.query = true;
    bus.lcm().publish("sim_server/gains/set", &q);
  }
  io.poll_until(monotonic_us());
  bus.lcm().handleTimeout(0);
  ASSERT_EQ(gains.messages.size(), 2u);
  const std::vector<pid_gains_t> before = gains.messages;
  const std::vector<std::pair<std::string, std::string>> channels{
      {"hardware/command", "hardware_command_t"}, {"e_stop", "e_stop_t"}, {"sim_server/gains/set", "pid_gains_t"},
      {"sim_server/request", "sim_request_t"}};  // queued for the stepper, which this test does not run
  lt::Payloads payloads(1123);
  for (const auto& [channel, type] : channels) {
    const int64_t steps = sim.step_count();
    Tally t = flood(
        bus.lcm(), channel, n,
        [&] {
          hints.integers = {io.session(), sim.step_count(), sim.step_count() - 1};
          return payload_of(payloads, type, hints);
        },
        [&] { io.poll_until(monotonic_us()); }, cycle);
    t.channel = "sim_server " + channel + " (" + type + ")";
    t.print("in-process, 1 Bullet step per 10 payloads");
    EXPECT_EQ(t.crashes, 0) << channel;
    EXPECT_EQ(t.hangs, 0) << channel;
    EXPECT_LT(double(t.log_bytes), 16384 * (t.seconds + 1)) << channel << ": the log grows with the flood";
    EXPECT_GT(sim.step_count(), steps + n / 10 - 1) << channel;
  }
  // Release an e-stop the flood may have left engaged, restore the gains, and the robot follows genuine commands.
  e_stop_t release{};
  release.engaged = false;
  bus.lcm().publish("e_stop", &release);
  for (pid_gains_t g : before) {
    g.query = false;
    bus.lcm().publish("sim_server/gains/set", &g);
  }
  for (int k = 0; k < 3000; ++k) cycle();
  bus.lcm().handleTimeout(0);
  int64_t bad = 0;
  for (const auto& s : states.messages)
    if (!finite(s.position) || !finite(s.velocity) || !finite(s.effort)) ++bad;
  std::printf("%zu hardware/state, %lld non-finite; dropped %lld, stale %lld; j1 at %.4f after 3 s of genuine commands\n",
              states.messages.size(), static_cast<long long>(bad), static_cast<long long>(io.dropped()),
              static_cast<long long>(io.stale()), states.messages.back().position[0]);
  EXPECT_EQ(bad, 0);
  EXPECT_NEAR(states.messages.back().position[0], 0.5, 0.05);
}

// What the tools decode from the bus: `clock` (turret-cmd's and bus pub's CommandClock, through the guarded
// subscription), and joint_states and every other channel through the field paths (state-logger, log2csv,
// plotter) and the YAML of `bus echo`.
TEST(Fuzz, ToolsTakeHostilePayloadsOnClockAndJointStates) {
  const int n = payloads_per_channel();
  Bus bus("memq://", "");
  tools::CommandClock clock(bus, 0);
  lt::Hints hints{{"j1", "j2"}, {0, 1000}};
  lt::Payloads payloads(7);
  Tally c = flood(
      bus.lcm(), "clock", n, [&] { return payload_of(payloads, "sim_clock_t", hints); },
      [&] { bus.lcm().handleTimeout(0); }, [] {});
  c.channel = "tools clock (sim_clock_t, CommandClock)";
  c.print("in-process");
  EXPECT_EQ(c.crashes + c.hangs, 0);
  // After the flood the clock still follows the simulator.
  sim_clock_t genuine{};
  genuine.utime = 123456;
  bus.lcm().publish("clock", &genuine);
  bus.lcm().handleTimeout(0);
  EXPECT_TRUE(clock.on_sim());
  EXPECT_EQ(clock.now_us(), 123456);

  int64_t decoded = 0, refused = 0, crashes = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < n; ++k) {
    const auto b = payload_of(payloads, "joint_state_t", hints);
    try {
      const tools::Decoded d = tools::decode_fields(b.data(), b.size());
      if (d.ok()) {
        ++decoded;
        tools::message_yaml(b.data(), b.size());
      } else {
        ++refused;
      }
    } catch (const std::runtime_error&) {
      ++refused;  // message_yaml's answer to bytes that are not a message
    } catch (...) {
      ++crashes;
    }
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("RELIABILITY|fuzz|tools joint_states (joint_state_t: field paths, bus echo's YAML)|tried=%d|ok=%lld|"
              "crashes=%lld|hangs=0|in-process; %lld decoded, %lld refused, %.2f s\n",
              n, static_cast<long long>(decoded + refused), static_cast<long long>(crashes),
              static_cast<long long>(decoded), static_cast<long long>(refused), s);
  EXPECT_EQ(crashes, 0);
}
