// The controller types built in (one registration line each in builtin.cpp): the controller manager, doctor and
// launch start from these, and a YAML's plugins add theirs.
#pragma once

#include "controller_interface/registry.hpp"

namespace lcm_control::cm {

const Registry& builtin_registry();
void register_builtin(Registry& registry);

}  // namespace lcm_control::cm
