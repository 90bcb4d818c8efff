#include "rt/loop_stats.hpp"

#include <algorithm>
#include <cmath>

namespace lcm_control {

namespace {
// The q-quantile of v (nearest rank), reordering v in place; 0 when empty.
double quantile_in_place(std::vector<double>& v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::ptrdiff_t>(std::ceil(q * static_cast<double>(v.size()))) - 1;
  const auto at = v.begin() + std::clamp<std::ptrdiff_t>(k, 0, static_cast<std::ptrdiff_t>(v.size()) - 1);
  std::nth_element(v.begin(), at, v.end());
  return *at;
}
}  // namespace

LoopStats::LoopStats() { errors_.reserve(kErrorCapacity); }

void LoopStats::add_cycle(int64_t start_us, int64_t work_us, bool overrun) {
  ++cycles_;
  if (last_start_us_ >= 0) {
    const double p = static_cast<double>(start_us - last_start_us_);
    ++periods_;
    p_sum_ += p;
    p_sq_ += p * p;
    p_min_ = std::min(p_min_, p);
    p_max_ = std::max(p_max_, p);
    if (nominal_us_ > 0 && errors_.size() < errors_.capacity()) errors_.push_back(std::abs(p - nominal_us_));
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
  m.period_error_p50_us = quantile_in_place(errors_, 0.5);
  m.period_error_p99_us = quantile_in_place(errors_, 0.99);
  m.overruns = overruns_;
  m.missed = missed_;
  m.dropped = dropped_;
  m.real_time_factor = rtf_;
  m.exec_mean_us = exec_.mean_us();
  m.exec_max_us = exec_.max_us;
  cycles_ = periods_ = overruns_ = missed_ = dropped_ = 0;
  p_sum_ = p_sq_ = p_max_ = 0;
  p_min_ = std::numeric_limits<double>::infinity();
  exec_.reset();
  rtf_ = 0;
  errors_.clear();  // keeps the reserved capacity; the last start and the nominal period carry over
}

}  // namespace lcm_control
