// Controller types by name (ros_controllers' pluginlib names), each with its declaration and factory: the built-in
// ones (controllers/builtin.hpp) are linked in (no plugin to build, install or source); your own come from libraries
// the YAML names, which add theirs here (plugin.hpp). The closest name by edit distance tells a misspelling.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "controller_interface/controller.hpp"
#include "controller_interface/controller_type.hpp"

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

 private:
  std::map<std::string, ControllerType> types_;
};

}  // namespace lcm_control::cm
