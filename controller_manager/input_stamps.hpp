// What the controller manager took in from the shared bus before each cycle, published as cm_inputs_t on
// `controller_manager/inputs` (the channel, the digest and the size of each message), so that a recording says at
// which cycle every external input acted and `replay` hands it over there, whatever order the recorder saw the bus
// in. Inputs are what changes the controllers: commands, goals, gains, e-stops, requests other than queries; not the
// hardware loop, not the simulator's channels. Stamped where the shared bus is read directly (udpm://, the programs'
// default: LcmSocket's tap).
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "bus/endpoints.hpp"
#include "lcm_control/cm_inputs_t.hpp"

namespace lcm_control::cm {

// Whether a message on `channel` (as on the bus, namespace included) is an input the manager acts on; the names it
// compares with are made once.
class InputFilter {
 public:
  explicit InputFilter(const Bus& bus);
  bool operator()(const std::string& channel, const void* data, size_t size) const;

 private:
  std::string hardware_, sim_, request_;
};

class InputStamps {
 public:
  static constexpr size_t kListed = 1000;  // inputs one stamp lists; beyond them, counted (cm_inputs_t::untaken)

  // Taps bus's shared socket (none: nothing is stamped) and publishes through `publisher`.
  InputStamps(Bus& bus, Publisher<cm_inputs_t> publisher);
  ~InputStamps();
  InputStamps(const InputStamps&) = delete;
  InputStamps& operator=(const InputStamps&) = delete;

  // A message the manager's subscriptions received.
  void taken(const std::string& channel, const void* data, size_t size);
  // The message just taken waits for work off the loop (a trajectory goal on the intake's thread, rt/intake.hpp): it
  // is stamped at the cycle after result_taken() says its result ran, in the order submitted.
  void submitted_off_loop();
  void result_taken();
  // Before the cycle of (session, step): publishes what was taken since the last one, if anything.
  void stamp(int64_t session, int64_t step);

 private:
  Bus& bus_;
  InputFilter is_input_;
  Publisher<cm_inputs_t> publisher_;
  cm_inputs_t pending_{};
  struct Input {
    std::string channel;
    int64_t digest = 0;
    int32_t size = 0;
  };
  bool add(Input input);  // false: over kListed, counted
  bool just_taken_ = false;                    // the last message of pending_ is the one being delivered
  std::deque<std::optional<Input>> deferred_;  // submitted off the loop, oldest first (none: one that was not taken)
};

}  // namespace lcm_control::cm
