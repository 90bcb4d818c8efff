// Helpers the tool tests share: CSV reading (the tools' own reader), file
// checks, and logs written as lcm-logger writes them.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tools/csv.hpp"

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

namespace lcm_control::testing {

// A log as lcm-logger writes it: 50 joint_states (2 joints) at 100 Hz, 20
// j2_controller/command at 40 Hz, one controller_manager/response and one
// channel of foreign bytes. Event times start at 1 s; utime is sim time.
inline void write_test_log(const std::string& path) {
  lcm::LogFile log(path, "w");
  int64_t event_number = 0;
  auto put = [&](const std::string& channel, int64_t t_us, const std::vector<uint8_t>& bytes) {
    lcm::LogEvent ev{};
    ev.eventnum = event_number++;
    ev.timestamp = 1000000 + t_us;
    ev.channel = channel;
    ev.datalen = int32_t(bytes.size());
    ev.data = const_cast<uint8_t*>(bytes.data());
    log.writeEvent(&ev);
  };
  auto bytes = [](const auto& m) {
    std::vector<uint8_t> b(size_t(m.getEncodedSize()));
    m.encode(b.data(), 0, int(b.size()));
    return b;
  };
  for (int k = 0; k < 50; ++k) {
    const int64_t t = k * 10000;
    joint_state_t js{};
    js.utime = t;
    js.num_joints = 2;
    js.name = {"j1", "j2"};
    js.position = {0.01 * k, std::sin(0.1 * k)};
    js.velocity = {0.5, std::cos(0.1 * k)};
    js.effort = {1.0 * k, -1.0 * k};
    put("joint_states", t, bytes(js));
    if (k < 40 && k % 2 == 0) {
      float64_t c{};
      c.utime = t + 5000;
      c.data = 3.14 * std::sin(k / 2 / 100.0);
      put("j2_controller/command", t + 5000, bytes(c));
    }
  }
  cm_response_t r{};
  r.message = "ok";
  put("controller_manager/response", 123, bytes(r));
  const std::string junk = "raw bytes, not lcm_control";
  put("other_robot/blob", 456, std::vector<uint8_t>(junk.begin(), junk.end()));
}

}  // namespace lcm_control::testing
