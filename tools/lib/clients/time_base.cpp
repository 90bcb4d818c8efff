#include "tools/lib/clients/time_base.hpp"

#include <fmt/format.h>

#include "tools/lib/clients/wait.hpp"

namespace lcm_control::tools {

TimeBase time_base(int64_t utime) { return utime >= 1000000000000000LL ? TimeBase::Wall : TimeBase::Sim; }

const char* time_base_name(TimeBase b) { return b == TimeBase::Sim ? "sim time" : "wall-clock time"; }

std::string mixed_clocks(const std::string& channel_a, int64_t utime_a, const std::string& channel_b,
                         int64_t utime_b) {
  const TimeBase a = time_base(utime_a), b = time_base(utime_b);
  if (a == b) return "";
  return fmt::format("{} is stamped in {} (utime {}) but {} in {} (utime {}), so their utimes cannot be compared",
                     channel_a, time_base_name(a), utime_a, channel_b, time_base_name(b), utime_b);
}

CommandClock::CommandClock(Bus& bus, double wait_s) : bus_(bus) {
  sub_ = subscribe_guarded<&CommandClock::on_clock>(bus, bus.channel(channels::kClock), this);
  pump_until(bus, [this] { return on_sim(); }, wait_s);
}

CommandClock::~CommandClock() { bus_.unsubscribe(sub_); }

void CommandClock::on_clock(const lcm::ReceiveBuffer*, const std::string&, const sim_clock_t* m) {
  if (m->utime >= 0 && time_base(m->utime) == TimeBase::Sim) sim_utime_ = m->utime;
}

}  // namespace lcm_control::tools
