#include "common/loop_stats.hpp"

#include <algorithm>
#include <cmath>

namespace lcm_control {

void LoopStats::add_cycle(int64_t start_us, int64_t work_us, bool overrun) {
  ++cycles_;
  if (last_start_us_ >= 0) {
    const double p = static_cast<double>(start_us - last_start_us_);
    ++periods_;
    p_sum_ += p;
    p_sq_ += p * p;
    p_min_ = std::min(p_min_, p);
    p_max_ = std::max(p_max_, p);
  }
  last_start_us_ = start_us;
  exec_.add(static_cast<double>(work_us));
  if (overrun) ++overruns_;
}

void LoopStats::fill_and_reset(loop_stats_t& m) {
  m.cycles = cycles_;
  const double n = static_cast<double>(periods_);
  m.period_mean_us = periods_ ? p_sum_ / n : 0.0;
  m.period_min_us = periods_ ? p_min_ : 0.0;
  m.period_max_us = p_max_;
  m.period_jitter_us = periods_ > 1 ? std::sqrt(std::max(0.0, p_sq_ / n - m.period_mean_us * m.period_mean_us)) : 0.0;
  m.overruns = overruns_;
  m.missed = missed_;
  m.dropped = dropped_;
  m.real_time_factor = rtf_;
  m.exec_mean_us = exec_.mean_us();
  m.exec_max_us = exec_.max_us;
  const int64_t keep = last_start_us_;
  *this = LoopStats{};
  last_start_us_ = keep;
}

}  // namespace lcm_control
