#include "test/controller_manager/alloc_counter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
thread_local bool g_counting = false;  // the loop's thread only: the outbox's sending thread is not the loop path
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  if (g_counting) g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace lcm_control::testing {
void count_allocations(bool on) { g_counting = on; }
long allocations() { return g_allocations; }
void reset_allocations() { g_allocations = 0; }
}  // namespace lcm_control::testing
