// `bus netcheck`: whether LCM multicast on this URL reaches other computers.
// Says what the URL allows (ttl), which interface multicast leaves by, whether
// scripts/lcm-firewall's table is installed, then probes on
// `lcm_control/netcheck` and lists every other netcheck that heard or answered.
#pragma once

#include "bus/bus.hpp"

namespace lcm_control::tools {

// duration_s: how long to probe (0 with answer_only: until Ctrl-C). answer_only: answer others, for a computer
// that another one checks. Returns 0 when another netcheck answered; throws BusError (exit 4) when none did.
int cmd_netcheck(Bus& bus, double duration_s, bool answer_only);

}  // namespace lcm_control::tools
