// libFuzzer target (scripts/libfuzz): the guarded decode every program applies to bus input, for every message
// type, and the hardware messages' count checks. The first input byte picks the type; the rest is the payload.
// Any crash, sanitizer report or exception escaping is a finding.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bus/bus.hpp"
#include "bus/hardware_wire.hpp"
#include "lcm_control/visit.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lcm_control;
  if (size < 1) return 0;
  const uint8_t pick = data[0];
  const uint8_t* payload = data + 1;
  const size_t n = size - 1;
  int index = 0, count = 0;
  for_each_type([&](auto) { ++count; });
  const int want = pick % count;
  for_each_type([&](auto tag) {
    using Msg = typename decltype(tag)::type;
    if (index++ != want) return;
    Msg m;
    if (decode_guarded(m, payload, n)) {
      // What decoded must encode again to the same size (the counts matched the arrays).
      std::vector<uint8_t> out(size_t(m.getEncodedSize()));
      if (m.encode(out.data(), 0, int(out.size())) != int(out.size())) __builtin_trap();
    }
  });
  (void)check_hardware_state_bytes(payload, n, 16);
  (void)check_hardware_command_bytes(payload, n, 16);
  return 0;
}
