// Counts C++ heap allocations (global operator new) made on the thread that
// turned counting on, to prove a code path allocates nothing. Linked into one
// test binary only.
#pragma once

namespace lcm_control::testing {

void count_allocations(bool on);
long allocations();
void reset_allocations();

}  // namespace lcm_control::testing
