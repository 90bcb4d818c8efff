// Command sources: the controller manager generates a controller's commands
// itself, on hardware time, from muparser expressions (command_source_t on
// `controller_manager/command_source`). Tick j is due j/rate after the first
// cycle in which the controller runs; its values are handed to the
// controller's command input (CommandInput, as numbers) before that cycle's
// update (so lockstep runs repeat exactly) and published on
// `<controller>/command` after the cycle. While a source runs it owns that channel: its own messages coming
// back from the bus are not delivered again (they may come after a newer
// tick), and another publisher's are ignored and counted in its end.
// before_update() and after_cycle() neither allocate nor log. A
// request sent again under its request_id (its answer was lost) gets the same
// answer and changes nothing.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bus/answer_ledger.hpp"
#include "bus/bus.hpp"
#include "rt/log.hpp"
#include "control/expression.hpp"
#include "controller_interface/controller.hpp"
#include "controller_manager/loop.hpp"
#include "controller_manager/reply.hpp"
#include "bus/endpoints.hpp"
#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/command_source_t.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"

namespace lcm_control::cm {

struct ControllerSlot;

class CommandSources : public BeforeUpdate {
 public:
  CommandSources(Loop& loop, Bus& bus);
  ~CommandSources();

  // Registers (or replaces) the source of req.controller, or with req.remove
  // ends it. The reply says what was set up or why not.
  Reply handle(const command_source_t& req);

  // Loop path: deliver the ticks due at `now` (after restarts, before updates).
  void before_update(const Time& now) override;
  // After the cycle: publish the values delivered in it on `<controller>/command`.
  void after_cycle();
  // Between cycles: answer the requests of ended sources and log them.
  void poll();

  // The controller is about to be unloaded: its source ends now.
  void end_for(const std::string& controller, const char* why);
  void end_all(const char* why);

  size_t active() const;
  // Ticks delivered by the source of `controller` (-1 if it has none).
  int64_t ticks(const std::string& controller) const;

 private:
  struct Source;
  struct Echoes;
  // A message from the bus on a channel a source owns: its own echo, or another publisher's (ignored, counted).
  void from_bus(Source& s, const lcm::ReceiveBuffer& rb);
  // The channel goes back to the controller's handlers.
  void give_back(Source& s);
  void answer(int64_t request_id, const Reply& reply);

  Loop& loop_;
  Bus& bus_;
  Endpoints endpoints_;
  Publisher<cm_response_t> response_pub_;
  std::vector<std::unique_ptr<Source>> sources_;
  AnswerLedger<cm_response_t> ledger_;  // a resent request is answered again, not registered twice
  BusLog log_;
};

}  // namespace lcm_control::cm
