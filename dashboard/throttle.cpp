#include "dashboard/throttle.hpp"

namespace lcm_control::dashboard {

void Throttle::roll(Channel& c, int64_t now_us) {
  const int64_t age = now_us - c.window_start_us;
  if (age < 1000000) return;
  // A window that ended long ago says nothing about now: the rate is what came in the last whole second.
  c.hz = age < 2000000 ? double(c.window_count) * 1e6 / double(age) : 0.0;
  c.window_start_us = now_us;
  c.window_count = 0;
}

void Throttle::offer(const std::string& channel, const void* data, size_t size, int64_t now_us, bool from_others) {
  if (from_others) last_us_ = now_us;
  if (channels_.size() >= kMaxChannels && !channels_.count(channel)) {
    ++ignored_;
    return;
  }
  auto [it, added] = channels_.try_emplace(channel);
  Channel& c = it->second;
  if (added) c.window_start_us = now_us;
  roll(c, now_us);
  if (c.fresh) ++c.skipped;
  const auto* p = static_cast<const uint8_t*>(data);
  c.bytes.assign(p, p + size);
  c.fresh = true;
  c.received_us = now_us;
  ++c.total;
  ++c.window_count;
}

std::vector<Throttle::Due> Throttle::take_due(int64_t now_us) {
  std::vector<Due> out;
  for (auto& [name, c] : channels_) {
    // A tenth of a period early is on time: the caller's timer wakes a little late or early.
    if (!c.fresh || (c.sent_us >= 0 && now_us - c.sent_us < period_us_ - period_us_ / 10)) continue;
    out.push_back(Due{name, c.bytes, c.received_us, c.skipped});
    c.fresh = false;
    c.skipped = 0;
    c.sent_us = now_us;
  }
  return out;
}

std::vector<Throttle::Rate> Throttle::rates(int64_t now_us) {
  std::vector<Rate> out;
  for (auto& [name, c] : channels_) {
    roll(c, now_us);
    out.push_back(Rate{name, c.hz, c.total, c.received_us});
  }
  return out;
}

}  // namespace lcm_control::dashboard
