// What reaches a browser from a busy bus: the newest message per channel, at most once per display period
// (latest wins), with each channel's message rate, so a 1 kHz loop costs a browser only the display rate.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace lcm_control::dashboard {

class Throttle {
 public:
  // period_us: the shortest time between two hand-outs of one channel (e.g. 33,333 for 30 Hz).
  explicit Throttle(int64_t period_us) : period_us_(period_us) {}

  // Keeps the newest payload of channel, received at now_us (monotonic). from_others false: a message the
  // dashboard sent itself, which does not make the bus count as alive. Past kMaxChannels channels (anyone on the bus
  // can invent names), messages on new ones are only counted in ignored().
  void offer(const std::string& channel, const void* data, size_t size, int64_t now_us, bool from_others = true);

  struct Due {
    std::string channel;
    std::vector<uint8_t> bytes;
    int64_t received_us = 0;
    int64_t skipped = 0;  // payloads replaced by a newer one since the last hand-out
  };
  // The channels with a payload not yet handed out whose last hand-out was at least a period before now_us (less a
  // tenth: a caller that asks once a period must not skip every other period for a late tick).
  std::vector<Due> take_due(int64_t now_us);

  // A channel's messages per second over the last whole second (lcm-spy's Hz).
  struct Rate {
    std::string channel;
    double hz = 0;
    int64_t total = 0;
    int64_t last_us = 0;
  };
  std::vector<Rate> rates(int64_t now_us);

  // The newest receive time of a message from others; -1 before the first.
  int64_t last_message_us() const { return last_us_; }
  int64_t ignored() const { return ignored_; }

  static constexpr size_t kMaxChannels = 1000;

 private:
  struct Channel {
    std::vector<uint8_t> bytes;
    bool fresh = false;
    int64_t received_us = 0, sent_us = -1, skipped = 0;
    int64_t total = 0, window_start_us = 0, window_count = 0;
    double hz = 0;
  };
  void roll(Channel& c, int64_t now_us);
  int64_t period_us_;
  int64_t last_us_ = -1, ignored_ = 0;
  std::map<std::string, Channel> channels_;
};

}  // namespace lcm_control::dashboard
