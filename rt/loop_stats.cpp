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

void ExecStats::add(double us) {
  sum_us += us;
  if (us > max_us) max_us = us;
  if (n == 0 || us < min_us) min_us = us;
  ++n;
  static const double inv_log_ratio = 1.0 / std::log(kBinRatio);
  const double b = us > kLowestUs ? std::log(us / kLowestUs) * inv_log_ratio : 0.0;
  ++bins[size_t(std::clamp(b, 0.0, double(kBins - 1)))];
}

double ExecStats::percentile_us(double q) const {
  if (n == 0) return 0.0;
  const auto rank = std::max<int64_t>(1, static_cast<int64_t>(std::ceil(q * static_cast<double>(n))));
  int64_t seen = 0;
  for (int b = 0; b < kBins; ++b) {
    seen += bins[size_t(b)];
    if (seen < rank) continue;
    return b == kBins - 1 ? max_us : std::clamp(kLowestUs * std::pow(kBinRatio, b + 0.5), min_us, max_us);
  }
  return max_us;
}

void add_item(loop_stats_t& m, const std::string& name, const char* kind, ExecStats& exec, ExecStats* period) {
  m.item.push_back(name);
  m.item_kind.push_back(kind);
  m.item_count.push_back(exec.n);
  m.item_exec_mean_us.push_back(exec.mean_us());
  m.item_exec_max_us.push_back(exec.max_us);
  m.item_exec_p99_us.push_back(exec.percentile_us(0.99));
  m.item_period_mean_us.push_back(period ? period->mean_us() : 0.0);
  m.item_period_max_us.push_back(period ? period->max_us : 0.0);
  m.item_period_p99_us.push_back(period ? period->percentile_us(0.99) : 0.0);
  m.num_items = static_cast<int32_t>(m.item.size());
  exec.reset();
  if (period) period->reset();
}

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
