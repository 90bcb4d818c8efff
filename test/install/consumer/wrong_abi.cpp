// Exports the plugin entry points by hand with an ABI version from the future.
#include "controller_interface/plugin.hpp"

extern "C" lcm_control::cm::PluginAbi lcm_control_plugin_abi() {
  lcm_control::cm::PluginAbi abi = lcm_control::cm::this_plugin_abi();
  abi.controller_abi += 100;
  return abi;
}
extern "C" void lcm_control_register_controllers(lcm_control::cm::Registry&) {}
