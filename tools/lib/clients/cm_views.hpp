// What `cmctl statistics`, `view-hardware-status` and `view-controller-chains` print (ROS 2's `ros2 control`
// introspection verbs): a statistics window of the controller manager (and sim_server's, when it publishes one), each
// hardware component with its interfaces' current values and claimants, and the graph from controllers through the
// interfaces they claim or read to the hardware components (text, or Graphviz dot).
#pragma once

#include <string>

#include "bus/bus.hpp"
#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/loop_stats_t.hpp"

namespace lcm_control::tools {

// One loop_stats_t as a table: the loop's period and work, then per item its updates, execution time and period
// (mean, p99, max; µs).
std::string statistics_text(const loop_stats_t& m);

// The next controller_manager/statistics (and sim_server/statistics if one comes in the same wait) as text; throws
// BusError naming the channel when none comes within timeout_s (they are published once a second).
std::string wait_statistics(Bus& bus, double timeout_s);

// From a LIST answer.
std::string hardware_status_text(const cm_response_t& list);
std::string controller_chains_text(const cm_response_t& list);
// The joint a claimed name ends at: itself for a joint; for a reference interface "<controller>/<dof>" (ROS 2
// chaining) that of its dof, through every listed link of the chain (a JTC's command_joints -> its PIDs' joints).
std::string joint_behind(const std::vector<controller_info_t>& listed, const std::string& name);
std::string controller_chains_dot(const cm_response_t& list);

}  // namespace lcm_control::tools
