// Limits, item 2 of issue 35: the heaviest requests within kMaxRequestNames, against a controller manager with
// 10,000 configured controllers running turret_bot's fake hardware at 1 kHz in real time. Each answer is at most
// 64 KB and the loop keeps answering the hardware while a request is served (before: one LOAD of 1,000 names held
// it for the whole request, a RELOAD for the whole YAML).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "bus/messages.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/loop_stats_t.hpp"
#include "test/controller_manager/fake_hardware.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"
#include "description/load.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control;

namespace {

constexpr int kConfigured = 10000, kNames = 1000;
constexpr size_t kMaxAnswerBytes = 64 * 1024;

int64_t wall_now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string name_of(int k) { return fmt::format("state_{:05}", k); }

std::vector<std::string> names(const std::string& prefix = "") {
  std::vector<std::string> v;
  for (int k = 0; k < kNames; ++k) v.push_back(prefix.empty() ? name_of(k) : prefix + std::to_string(k));
  return v;
}

// joint_state_controllers that publish once in 1,000 s: 1,000 of them run together without flooding the bus.
std::string write_config(const std::string& folder) {
  const std::string path = folder + "/many.yaml";
  std::ofstream out(path);
  for (int k = 0; k < kConfigured; ++k)
    out << name_of(k) << ":\n  type: joint_state_controller/JointStateController\n  publish_rate: 0.001\n";
  return path;
}

struct Figures {
  std::string kind;
  int answer_bytes = 0;
  bool ok = false;
  double longest_gap_ms = 0;  // between two hardware/commands arriving while the request was served
  int commands = 0;           // hardware/commands answered while it was served
  double served_ms = 0;
};

}  // namespace

TEST(Limits, RequestsWithinTheLimitsNeitherStallTheLoopNorAnswerOver64KB) {
  const std::string folder = lt::temp_dir("limits_requests");
  const std::string config = write_config(folder), urdf = lt::source("config/turret_bot.urdf");
  const std::string url = lt::unique_lcm_url();
  lt::ChildProcess cm({lt::bin("controller_manager"), "--urdf", urdf, "--config", config, "--lcm-url", url});
  ASSERT_TRUE(cm.wait_for_output("ready (", 120)) << cm.output();
  lcm::LCM lc(url);
  lt::Recorder<cm_response_t> responses(lc, "controller_manager/response");
  lt::Recorder<hardware_command_t> commands(lc, "hardware/command");
  lt::Recorder<loop_stats_t> stats(lc, "controller_manager/statistics");
  lt::FakeHardwareOptions o;
  o.lockstep = false;
  o.period_us = 1000;
  lt::FakeHardware hw(url, lt::actuators_for(load_robot_model(urdf, std::vector<std::string>{})), o);
  hw.start();
  ASSERT_TRUE(lt::pump_until(lc, [&] { return commands.messages.size() > 500; }, 20)) << cm.output();

  // The noise floor: the longest gap in half a second without requests.
  const size_t quiet0 = commands.arrival_us.size();
  lt::pump_until(lc, [] { return false; }, 0.5);
  double quiet_ms = 0;
  for (size_t k = quiet0 + 1; k < commands.arrival_us.size(); ++k)
    quiet_ms = std::max(quiet_ms, (commands.arrival_us[k] - commands.arrival_us[k - 1]) * 1e-3);

  int64_t id = 1;
  std::vector<Figures> figures;
  auto call = [&](const std::string& kind, cm_request_t r) -> const cm_response_t* {
    r.request_id = id++;
    r.client = "limits_test";
    const size_t first = commands.arrival_us.size();
    const int64_t sent = wall_now_us();
    lc.publish("controller_manager/request", &r);
    const cm_response_t* answer = nullptr;
    lt::pump_until(lc, [&] {
      for (const auto& m : responses.messages)
        if (m.request_id == r.request_id) answer = &m;
      return answer != nullptr;
    }, 120);
    if (!answer) {
      ADD_FAILURE() << kind << ": no answer in 120 s\n" << cm.output();
      return nullptr;
    }
    const int64_t answered = responses.arrival_us[size_t(answer - responses.messages.data())];
    lt::pump_until(lc, [] { return false; }, 0.02);  // the commands that arrived meanwhile
    Figures f{kind, answer->getEncodedSize(), answer->ok != 0};
    int64_t last = first > 0 ? commands.arrival_us[first - 1] : sent;
    for (size_t k = first; k < commands.arrival_us.size(); ++k) {
      const int64_t t = commands.arrival_us[k];
      if (t > answered) {
        f.longest_gap_ms = std::max(f.longest_gap_ms, (t - last) * 1e-3);
        break;
      }
      f.longest_gap_ms = std::max(f.longest_gap_ms, (t - last) * 1e-3);
      last = t;
      ++f.commands;
    }
    f.served_ms = (answered - sent) * 1e-3;
    figures.push_back(f);
    EXPECT_LE(size_t(f.answer_bytes), kMaxAnswerBytes) << kind << ": " << answer->message.substr(0, 400);
    return answer;
  };

  const cm_response_t* a = call("load 1000 unknown", cm_request(cm_request_t::LOAD, names("nope_")));
  ASSERT_TRUE(a && !a->ok);
  a = call("load 1000", cm_request(cm_request_t::LOAD, names()));
  ASSERT_TRUE(a && a->ok) << a->message.substr(0, 400);
  a = call("list 1000 loaded", cm_request(cm_request_t::LIST));
  ASSERT_TRUE(a && a->ok);
  EXPECT_NE(a->message.find(fmt::format(" of {} controllers listed, in load order: an answer is at most 64 KB", kNames)),
            std::string::npos)
      << a->message;
  a = call("switch start 1000", cm_request(cm_request_t::SWITCH, {}, names()));
  ASSERT_TRUE(a && a->ok) << a->message.substr(0, 400);
  a = call("switch stop 1000", cm_request(cm_request_t::SWITCH, {}, {}, names()));
  ASSERT_TRUE(a && a->ok) << a->message.substr(0, 400);
  a = call("unload 1000", cm_request(cm_request_t::UNLOAD, names()));
  ASSERT_TRUE(a && a->ok) << a->message.substr(0, 400);
  a = call("reload 10000 configured", cm_request(cm_request_t::RELOAD));
  ASSERT_TRUE(a && a->ok) << a->message.substr(0, 400);
  ASSERT_TRUE((a = call("load 1000 again", cm_request(cm_request_t::LOAD, names()))) && a->ok);
  ASSERT_TRUE((a = call("start 1000 again", cm_request(cm_request_t::SWITCH, {}, names()))) && a->ok);
  cm_request_t force = cm_request(cm_request_t::RELOAD);
  force.force = true;
  a = call("reload force, 1000 running", force);
  ASSERT_TRUE(a && a->ok) << a->message.substr(0, 400);
  // After a forced reload of 10,000 (before: 1.2-1.4 s for each LOAD of unknown names, and Ctrl-C ended with launch
  // killing the controller manager).
  a = call("load 1000 unknown after the forced reload", cm_request(cm_request_t::LOAD, names("nope_")));
  ASSERT_TRUE(a && !a->ok);
  EXPECT_LT(figures.back().served_ms, 500.0) << a->message.substr(0, 400);
  hw.stop();

  double worst_period_ms = 0, worst_cycle_ms = 0;  // the controller manager's own figures, every 1 s window of the run
  for (const auto& s : stats.messages) {
    worst_period_ms = std::max(worst_period_ms, s.period_max_us * 1e-3);
    worst_cycle_ms = std::max(worst_cycle_ms, s.exec_max_us * 1e-3);
  }
  std::string line;
  int largest = 0;
  double longest = 0;
  for (const auto& f : figures) {
    line += fmt::format("{}: {} B answer, longest command gap {:.2f} ms ({} commands in {:.0f} ms); ", f.kind,
                        f.answer_bytes, f.longest_gap_ms, f.commands, f.served_ms);
    largest = std::max(largest, f.answer_bytes);
    longest = std::max(longest, f.longest_gap_ms);
  }
  // Bounds that machine noise cannot reach but a request holding the loop does (before: 300 ms and more while a
  // reload read the YAML, no command answered meanwhile): the goal, 2 ms, is in the figures, against the noise floor.
  for (const auto& f : figures)
    if (f.served_ms > 100) {
      EXPECT_GT(f.commands, f.served_ms / 2) << f.kind << ": the loop stopped answering";
    }
  EXPECT_LT(longest, 50.0) << "a request held the loop";
  std::printf("RELIABILITY|limits|requests within the limits against 10,000 configured controllers at 1 kHz|tried=%zu|"
              "ok=%d|crashes=0|hangs=0|largest answer %d B, longest command gap %.2f ms (%.2f ms in 0.5 s without "
              "requests), controller_manager's longest period %.2f ms and longest cycle %.2f ms (a switch of 1,000 "
              "applied in one); %s\n",
              figures.size(), ::testing::Test::HasFailure() ? 0 : int(figures.size()), largest, longest, quiet_ms,
              worst_period_ms, worst_cycle_ms, line.c_str());
  // Within launch's own --stop-timeout (5 s), as Ctrl-C on launch gives it.
  const auto stop0 = std::chrono::steady_clock::now();
  EXPECT_EQ(cm.stop(5), 0) << cm.output().substr(0, 4000);
  std::printf("controller_manager with 10,000 configured stopped in %.2f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - stop0).count());
  std::filesystem::remove_all(folder);
}
