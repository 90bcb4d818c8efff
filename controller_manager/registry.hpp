// Controller types by name (ros_controllers' pluginlib names): the built-in
// ones are linked in (no plugin to build, install or source); your own come
// from libraries the YAML names (plugins.hpp). Unknown names get the list of
// valid types and the closest one by edit distance.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "controller_manager/controller.hpp"
#include "controller_manager/controller_type.hpp"

namespace lcm_control::cm {

class Registry {
 public:
  void add(ControllerType type);
  // A type that says nothing of itself but its name.
  void add(const std::string& type, Factory factory);
  void merge(Registry&& other);  // adds other's types
  bool has(const std::string& type) const { return types_.count(type) > 0; }
  std::unique_ptr<Controller> create(const std::string& type) const;  // nullptr if unknown
  const ControllerTypeInfo* info(const std::string& type) const;      // nullptr if unknown
  std::vector<std::string> types() const;                             // sorted
  // The registered type nearest to `type` (edit distance; a bare class name
  // such as "JointPositionControler" is compared with the class part too).
  std::string closest(const std::string& type) const;
  // Whether `type`, not registered, is a misspelling of a registered one (the nearest is at most 3 edits away and
  // under an eighth of the name): then it is an error. Any other unknown type is another package's, not available
  // here: its controller is skipped, the rest run.
  bool misspelling(const std::string& type) const;
  // A misspelling: "controller type 'x' does not exist; did you mean 'y'? Valid types: ..."; another package's
  // type: "controller type 'x' (ros_controllers) is not implemented here ..." or "... is not available here ...".
  std::string unknown_type_message(const std::string& type) const;

 private:
  std::map<std::string, ControllerType> types_;
};

// Every built-in type (see registry.cpp for the list).
const Registry& builtin_registry();
void register_builtin(Registry& registry);

}  // namespace lcm_control::cm
