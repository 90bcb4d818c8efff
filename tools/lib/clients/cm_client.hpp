// Client of the controller manager's services for cmctl and spawner:
// one cm_request_t on `controller_manager/request`, the cm_response_t with the
// same request_id back on `controller_manager/response`, within a timeout.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/command_source_t.hpp"
#include "lcm_control/hardware_command_t.hpp"

namespace lcm_control::tools {

// No answer in time. A BusError, so run_program exits with kExitBus.
class CmTimeout : public BusError {
 public:
  explicit CmTimeout(const std::string& what, std::string hint = "") : BusError(what), hint(std::move(hint)) {}
  std::string hint;  // NamespaceProbe's "did you mean --namespace NS?" line, or ""
};

class CmClient {
 public:
  CmClient(Bus& bus, std::string client);
  ~CmClient();  // unsubscribes: an answer that comes later (a command source ending) must not reach a dead client
  CmClient(const CmClient&) = delete;
  CmClient& operator=(const CmClient&) = delete;

  // Sends req (request_id and client filled in) and waits up to timeout_s for
  // its answer. Throws CmTimeout naming both channels; returns refusals as they are.
  // UDP can lose the request or the answer (a busy bus overflows a slow
  // reader's socket), so after each second without an answer it asks LIST:
  // if the list shows the load / unload / switch done, that is the answer
  // (ok, message says so); if not, it sends the request again. LIST and
  // LIST_TYPES are simply sent again. When after kHintAfterUs no answer came and a robot is heard only under
  // another namespace (NamespaceProbe), it throws CmTimeout at once with "did you mean --namespace NS?".
  cm_response_t call(cm_request_t req, double timeout_s);

  cm_response_t list(double timeout_s);
  cm_response_t list_types(double timeout_s);
  cm_response_t load(const std::vector<std::string>& names, double timeout_s);
  cm_response_t unload(const std::vector<std::string>& names, double timeout_s);
  cm_response_t switch_controllers(const std::vector<std::string>& start, const std::vector<std::string>& stop,
                                   bool strict, double timeout_s);
  cm_response_t reload(bool force, double timeout_s);
  // state: hardware_command_t::COMPONENT_*.
  cm_response_t set_component_state(const std::string& component, int8_t state, double timeout_s);

  // Registers (or with remove ends) a controller's command source on
  // `controller_manager/command_source`; returns the manager's answer. Sent
  // again every kResendS under the same request_id until answered: the
  // manager registers it once and repeats its answer. Throws CmTimeout.
  // The manager answers again with the same request_id when the source ends:
  // source_ended() polls for that answer (a repeat of the first is not it).
  cm_response_t command_source(command_source_t req, double timeout_s);
  std::optional<cm_response_t> source_ended(int64_t request_id, double timeout_s);

  // Asks LIST every 0.5 s until the manager answers (it may still be starting).
  // Throws CmTimeout after timeout_s; on_wait runs once if the first try is not answered.
  cm_response_t wait_for_manager(double timeout_s, const std::function<void()>& on_wait = {});

  std::string request_channel() const;
  std::string response_channel() const;

 private:
  void on_response(const lcm::ReceiveBuffer*, const std::string&, const cm_response_t* m);
  std::string no_answer(const std::string& what, double timeout_s) const;
  // Publishes req under a fresh id, remembered in ids; returns the id.
  int64_t send(cm_request_t& req, std::set<int64_t>& ids);
  // Waits up to timeout_s for an answer to any of ids.
  std::optional<cm_response_t> wait_answer(const std::set<int64_t>& ids, double timeout_s);

  Bus& bus_;
  std::string client_;
  int sub_ = 0;
  std::map<int64_t, cm_response_t> answers_;
  std::map<int64_t, int64_t> registered_;  // command source request_id -> utime of its registration's answer
  static constexpr double kResendS = 0.5;
  // How long call() waits for its answer before it names a manager heard only in another namespace.
  static constexpr int64_t kHintAfterUs = 300000;
};

// `message` without its leading "<controller>: " (a controller's result names itself).
std::string without_controller_prefix(const std::string& message, const std::string& controller);
// Why no result came from `controller` on `<controller>/result` within timeout_s, from what the manager says of it
// now; `longer` is what to do when it runs and sent `feedback` messages for the goal (e.g. "give a longer --timeout").
std::string no_goal_result(CmClient& cm, const Bus& bus, const std::string& controller, double timeout_s,
                           size_t feedback, const std::string& longer);

// "name  type  state  joints  interface" as an aligned table, one controller a line; with ros2, states as ROS 2
// names them (ros2_state).
std::string controller_table(const std::vector<controller_info_t>& controllers, bool ros2 = false, bool verbose = false);
// Rows as columns two spaces apart, each as wide as its widest cell: left-aligned, from column `right_from` on
// right-aligned (numbers).
std::string table_text(const std::vector<std::vector<std::string>>& rows, size_t right_from = SIZE_MAX);
// ROS 2's name of a controller state: running -> active, initialized and stopped -> inactive.
std::string ros2_state(const std::string& state);
// ROS 2's `list_hardware_interfaces`: "command interfaces" then "state interfaces", one JOINT/INTERFACE a line,
// command ones marked [available] and [claimed].
std::string hardware_interfaces_text(const std::vector<joint_interfaces_t>& joints);
// ROS 2's `list_hardware_components`: each component's state, type, plugin, joints, other state interfaces and the
// controllers using it.
std::string hardware_components_text(const std::vector<hardware_component_t>& components, bool verbose = false);

}  // namespace lcm_control::tools
