// Helpers the tool tests share: CSV reading (the tools' own reader), file
// checks, and logs written as lcm-logger writes them.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tools/lib/messages/csv.hpp"

namespace lcm_control::testing {

using Csv = tools::CsvTable;
using tools::read_csv;

inline std::vector<std::string> split(const std::string& line, char sep = ',') {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, sep)) out.push_back(cell);
  if (!line.empty() && line.back() == sep) out.push_back("");
  return out;
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace lcm_control::testing

#include <lcm/lcm-cpp.hpp>

#include <cmath>

#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"

namespace lcm_control::testing {

// A log file as lcm-logger writes it; event times are 1 s + t_us.
class TestLog {
 public:
  explicit TestLog(const std::string& path) : log_(path, "w") {}
  void put(const std::string& channel, int64_t t_us, const std::vector<uint8_t>& bytes) {
    lcm::LogEvent ev{};
    ev.eventnum = event_number_++;
    ev.timestamp = 1000000 + t_us;
    ev.channel = channel;
    ev.datalen = int32_t(bytes.size());
    ev.data = const_cast<uint8_t*>(bytes.data());
    log_.writeEvent(&ev);
  }
  template <class Msg>
  void put_message(const std::string& channel, int64_t t_us, const Msg& m) {
    std::vector<uint8_t> b(size_t(m.getEncodedSize()));
    m.encode(b.data(), 0, int(b.size()));
    put(channel, t_us, b);
  }

 private:
  lcm::LogFile log_;
  int64_t event_number_ = 0;
};

// A log as lcm-logger writes it: 50 joint_states (2 joints) at 100 Hz, 20
// j2_controller/command at 40 Hz, one controller_manager/response and one
// channel of foreign bytes. Event times start at 1 s; utime is sim time.
inline void write_test_log(const std::string& path) {
  TestLog log(path);
  for (int k = 0; k < 50; ++k) {
    const int64_t t = k * 10000;
    joint_state_t js{};
    js.utime = t;
    js.num_joints = 2;
    js.name = {"j1", "j2"};
    js.position = {0.01 * k, std::sin(0.1 * k)};
    js.velocity = {0.5, std::cos(0.1 * k)};
    js.effort = {1.0 * k, -1.0 * k};
    log.put_message("joint_states", t, js);
    if (k < 40 && k % 2 == 0) {
      float64_t c{};
      c.utime = t + 5000;
      c.data = 3.14 * std::sin(k / 2 / 100.0);
      log.put_message("j2_controller/command", t + 5000, c);
    }
  }
  cm_response_t r{};
  r.message = "ok";
  log.put_message("controller_manager/response", 123, r);
  const std::string junk = "raw bytes, not lcm_control";
  log.put("other_robot/blob", 456, std::vector<uint8_t>(junk.begin(), junk.end()));
}

// trajectory_status_t messages: the controller's goal-tolerance text (commas) and one with quotes and a line break.
inline const std::string kGoalToleranceText =
    "goal tolerance violated on joint 'j1': error 0.500000 (tolerance 0.100000), velocity 0.000000 (stopped "
    "tolerance 0.010000), 0.250 s after the trajectory end (goal_time 0.200)";
inline const std::string kRejectedText = "goal 3 rejected: joint \"j3\" is not controlled\nknown joints: j1, j2";

// trajectory_status_t of one joint j1 at 100 Hz: goal_id k+1, status ACTIVE with no text, then
// GOAL_TOLERANCE_VIOLATED with kGoalToleranceText, then REJECTED with kRejectedText; error[0] = 0.5 * k.
inline trajectory_status_t trajectory_status(int k) {
  trajectory_status_t s{};
  s.utime = 10000 * k;
  s.goal_id = k + 1;
  const int8_t status[] = {trajectory_status_t::ACTIVE, trajectory_status_t::GOAL_TOLERANCE_VIOLATED,
                           trajectory_status_t::REJECTED};
  s.status = status[k % 3];
  s.message = k % 3 == 0 ? "" : k % 3 == 1 ? kGoalToleranceText : kRejectedText;
  s.num_joints = 1;
  s.joint_names = {"j1"};
  s.desired = {1.0};
  s.actual = {1.0 - 0.5 * k};
  s.error = {0.5 * k};
  return s;
}

// A log of three trajectory_status_t (trajectory_status(0..2)) on arm_controller/status.
inline void write_status_log(const std::string& path) {
  TestLog log(path);
  for (int k = 0; k < 3; ++k) log.put_message("arm_controller/status", 10000 * k, trajectory_status(k));
}

}  // namespace lcm_control::testing
