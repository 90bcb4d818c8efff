#include "xacro/budget.hpp"

#include <fmt/format.h>

#include <pthread.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>

#include "xacro/process_error.hpp"

namespace lcm_control::xacro {

struct BudgetCounters {
  static const Budget& budget(const BudgetScope& s) { return s.budget_; }
  static BudgetUse& use(BudgetScope& s) { return s.use_; }
};

namespace {

thread_local BudgetScope* in_force = nullptr;

std::size_t times(std::size_t n, double factor) {
  const double v = std::ceil(static_cast<double>(n) * factor);
  return v >= static_cast<double>(std::numeric_limits<std::size_t>::max()) ? std::numeric_limits<std::size_t>::max()
                                                                          : static_cast<std::size_t>(std::max(1.0, v));
}

// `what` holds {} for the size.
[[noreturn]] void over(const char* what, std::size_t size, std::size_t limit, const char* unit) {
  throw ProcessError(fmt::format(
      "expansion budget exceeded: {}; the budget is {} {}, hundreds of times what real robots build. If the file is "
      "meant to build this much, raise every budget by a factor with LCM_CONTROL_XACRO_BUDGET=FACTOR (or xacro "
      "--budget FACTOR)",
      fmt::format(fmt::runtime(what), size), limit, unit));
}

}  // namespace

Budget Budget::scaled(double factor) const {
  return Budget{times(string_bytes, factor), times(list_items, factor), times(operations, factor), times(nodes, factor),
                times(macro_calls, factor), times(includes, factor), times(document_bytes, factor)};
}

BudgetScope::BudgetScope(const Budget& budget) : budget_(budget), previous_(in_force) { in_force = this; }
BudgetScope::~BudgetScope() { in_force = previous_; }

namespace {

// A size against one budget: kept as the largest seen (`add` false) or added to the total (`add` true).
void account(std::size_t Budget::*limit_of, std::size_t BudgetUse::*use_of, std::size_t n, bool add, const char* what,
             const char* unit) {
  if (!in_force) return;
  const std::size_t limit = BudgetCounters::budget(*in_force).*limit_of;
  std::size_t& used = BudgetCounters::use(*in_force).*use_of;
  const std::size_t size = add ? used + n : n;
  if (size > limit) over(what, size, limit, unit);
  used = add ? size : std::max(used, size);
}

}  // namespace

void check_string(std::size_t bytes) {
  account(&Budget::string_bytes, &BudgetUse::largest_string, bytes, false, "a string of {} bytes", "bytes");
}
void check_list(std::size_t items) {
  account(&Budget::list_items, &BudgetUse::largest_list, items, false, "a list of {} items", "items");
}
void count_operation() {
  account(&Budget::operations, &BudgetUse::operations, 1, true, "{} evaluation steps", "steps");
}
void count_nodes(std::size_t n) { account(&Budget::nodes, &BudgetUse::nodes, n, true, "{} XML nodes made", "nodes"); }
void count_macro_call() {
  account(&Budget::macro_calls, &BudgetUse::macro_calls, 1, true, "{} macro calls", "calls");
}
void count_include() { account(&Budget::includes, &BudgetUse::includes, 1, true, "{} files included", "includes"); }
void count_document_bytes(std::size_t bytes) {
  account(&Budget::document_bytes, &BudgetUse::document_bytes, bytes, true, "{} bytes of document text", "bytes");
}

void check_document(std::size_t bytes) {
  if (!in_force) return;
  const std::size_t limit = BudgetCounters::budget(*in_force).document_bytes;
  if (bytes > limit) over("a written document of {} bytes", bytes, limit, "bytes");
}

bool stack_nearly_full() {
  thread_local uintptr_t lowest = [] {  // the lowest usable address of this thread's stack, found once
    pthread_attr_t attr;
    void* base = nullptr;
    size_t size = 0, guard = 0;
    if (pthread_getattr_np(pthread_self(), &attr) != 0) return uintptr_t{0};
    pthread_attr_getstack(&attr, &base, &size);
    pthread_attr_getguardsize(&attr, &guard);
    pthread_attr_destroy(&attr);
    return reinterpret_cast<uintptr_t>(base) + guard;
  }();
  const auto here = reinterpret_cast<uintptr_t>(__builtin_frame_address(0));
  return lowest != 0 && here < lowest + kStackReserve;
}

}  // namespace lcm_control::xacro
