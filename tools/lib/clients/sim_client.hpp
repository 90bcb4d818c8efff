// Client of sim_server's simulation service for cmctl (pause, resume, step,
// reset, status): one sim_request_t on `sim_server/request`, its
// sim_response_t back on `sim_server/response`.
#pragma once

#include <cstdint>
#include <array>
#include <map>
#include <string>

#include "bus/bus.hpp"
#include "lcm_control/sim_request_t.hpp"
#include "lcm_control/sim_response_t.hpp"
#include "description/initial_positions.hpp"

namespace lcm_control::tools {

class SimClient {
 public:
  SimClient(Bus& bus, std::string client);
  ~SimClient();
  SimClient(const SimClient&) = delete;
  SimClient& operator=(const SimClient&) = delete;

  // Sends req and waits up to timeout_s for its answer, sending it again (same request_id: sim_server acts once)
  // after each second without one; a STEP waits its steps' sim time on top, at the control period a STATUS
  // reports. Throws BusError naming both channels when nothing comes; returns refusals as they are.
  sim_response_t call(sim_request_t req, double timeout_s);

  sim_response_t status(double timeout_s);
  sim_response_t pause(double timeout_s);
  sim_response_t resume(double timeout_s);
  sim_response_t step(int64_t steps, double timeout_s);
  sim_response_t reset(const InitialPositions& start, double timeout_s);
  // The FAIL_COMPONENT test hook: `component` fails as a lost device would, with `reason`.
  sim_response_t fail_component(const std::string& component, const std::string& reason, double timeout_s);
  // Gazebo's apply_body_wrench (sim_request_t::APPLY_WRENCH): force [N] and torque [N*m], world frame.
  sim_response_t apply_wrench(const std::string& link, const std::array<double, 3>& force,
                              const std::array<double, 3>& torque, double duration_s, double timeout_s);

 private:
  void on_response(const lcm::ReceiveBuffer*, const std::string&, const sim_response_t* m);
  Bus& bus_;
  std::string client_;
  int sub_ = 0;
  std::map<int64_t, sim_response_t> answers_;
};

// A sentence naming the request for messages ("step 100", "reset").
std::string sim_request_name(const sim_request_t& req);

}  // namespace lcm_control::tools
