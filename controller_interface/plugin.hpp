// What a library of your own controller types exports, as pluginlib's
// PLUGINLIB_EXPORT_CLASS does for ros_control. In one .cpp of the library, each type declared as a built-in one is
// (controller_type.hpp: its parameters, claims, command), so that doctor, list-types and the dashboard know it:
//   LCM_CONTROL_CONTROLLER_PLUGIN([](lcm_control::cm::Registry& r) {
//     r.add(ControllerType{info, [](const std::string&) { return std::make_unique<Sine>(); }});
//   })
// (docs/examples/my_controllers/sine_controller.cpp), linked to lcm_control::controller_interface alone.
// and name the library in the controller's YAML entry (`plugin: lib/libmy_controllers.so`). The controller
// manager checks the library was built against the same controller interface (PluginAbi) before it registers
// anything, and refuses it naming the file otherwise.
#pragma once

#include <cstddef>

#include "controller_interface/controller.hpp"
#include "controller_interface/registry.hpp"

namespace lcm_control::cm {

// Raise when Controller, ControllerContext, Registry or what they hand out (JointData, Params, Endpoints) changes.
inline constexpr int kControllerAbi = 8;  // 2: Port became lcm_control::Endpoints (bus/endpoints.hpp); 3: publishers
                                          // hand messages to an Outbox; 4: CommandInput (take_commands); 5: the
                                          // Registry keeps ControllerTypeInfo (controller_type.hpp); 6: a Claim's
                                          // interface per joint, JointData::owned_as, ClaimInfo::also; 7:
                                          // hardware components (JointData::component, Controller::uses()),
                                          // Controller::fail(); 8: the controller_interface library (an abstract
                                          // ControllerContext the manager implements, handles.hpp,
                                          // ControllerTypeInfo::chainable and references)

// What must match between the controller manager and a library: the interface version, the C++ library's string
// ABI, and the layout of the classes the two share.
struct PluginAbi {
  int controller_abi;
  int cxx11_string_abi;
  std::size_t controller_size, context_size, joint_data_size;
};

inline PluginAbi this_plugin_abi() {
  return {kControllerAbi, _GLIBCXX_USE_CXX11_ABI, sizeof(Controller), sizeof(ControllerContext), sizeof(JointData)};
}

inline bool operator==(const PluginAbi& a, const PluginAbi& b) {
  return a.controller_abi == b.controller_abi && a.cxx11_string_abi == b.cxx11_string_abi &&
         a.controller_size == b.controller_size && a.context_size == b.context_size &&
         a.joint_data_size == b.joint_data_size;
}

}  // namespace lcm_control::cm

#define LCM_CONTROL_CONTROLLER_PLUGIN(register_types)                                                   \
  extern "C" lcm_control::cm::PluginAbi lcm_control_plugin_abi() { return lcm_control::cm::this_plugin_abi(); } \
  extern "C" void lcm_control_register_controllers(lcm_control::cm::Registry& registry) { register_types(registry); }
