// A loop's timing over one statistics window (loop_stats_t, about once a second
// from both ends of the hardware loop): wall-clock period between cycle starts,
// the loop's own work per cycle, its error against the nominal period
// (percentiles), overruns, missed steps, dropped messages, and execution time
// per item (a controller, the physics step). add_*() are on the loop path: no
// allocation.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <limits>
#include <vector>

#include "lcm_control/loop_stats_t.hpp"

namespace lcm_control {

// Durations (an execution time, a period) over one window: count, mean, max, and percentiles read from a histogram
// of log-spaced bins (2 % wide, 0.1 µs to 100 s; a percentile is its bin's middle, within [min, max]; past the last
// bin, the max), so add() neither allocates nor sorts.
struct ExecStats {
  static constexpr double kLowestUs = 0.1, kBinRatio = 1.02;
  static constexpr int kBins = 1050;
  double sum_us = 0, max_us = 0, min_us = 0;
  int64_t n = 0;
  std::array<uint32_t, kBins> bins{};
  void add(double us);
  double mean_us() const { return n ? sum_us / static_cast<double>(n) : 0.0; }
  double percentile_us(double q) const;  // q in (0, 1]; 0 when empty
  void reset() { *this = ExecStats{}; }
};

// Appends one item to `m` (loop_stats_t's per-item arrays): its execution times and, when given, its periods, then
// starts their new windows. `kind`: "controller", "stage", ...
void add_item(loop_stats_t& m, const std::string& name, const char* kind, ExecStats& exec, ExecStats* period);

class LoopStats {
 public:
  LoopStats();
  // One cycle that started at start_us (monotonic; the period is taken between starts) and did work_us of work;
  // `overrun`: it ended late, by the loop's own rule (the controller manager: work longer than the period;
  // sim_server: its state published a period or more after its deadline).
  void add_cycle(int64_t start_us, int64_t work_us, bool overrun);
  void add_missed(int64_t n) { missed_ += n; }
  void add_dropped(int64_t n) { dropped_ += n; }
  void set_real_time_factor(double f) { rtf_ = f; }
  // The period the loop keeps in real time, for the error percentiles; 0 (lockstep, the default): none are taken.
  void set_nominal_period_us(double p) { nominal_us_ = p; }

  // Fills the timing fields (not the items) and starts a new window.
  void fill_and_reset(loop_stats_t& m);
  int64_t cycles() const { return cycles_; }

  // Period errors kept per window for the percentiles: a 1 s window at up to 8 kHz; past it, the first ones count.
  static constexpr size_t kErrorCapacity = 8192;

 private:
  int64_t cycles_ = 0, periods_ = 0, overruns_ = 0, missed_ = 0, dropped_ = 0;
  int64_t last_start_us_ = -1;
  double p_sum_ = 0, p_sq_ = 0, p_min_ = std::numeric_limits<double>::infinity(), p_max_ = 0;
  ExecStats exec_;
  double rtf_ = 0, nominal_us_ = 0;
  std::vector<double> errors_;  // |period - nominal| this window; reserved once, never grown on the loop path
};

}  // namespace lcm_control
