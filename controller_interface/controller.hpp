// What a controller is: init() reads its YAML and claims joints (not real
// time), then starting() / update() / stopping() run on the loop path and must
// not allocate, log or lock. Commands reach a controller through LCM handlers
// that run in the loop's own thread between cycles (numbers through
// take_commands), so plain members suffice.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "control/pid.hpp"
#include "description/robot_model.hpp"
#include "controller_interface/claims.hpp"
#include "controller_interface/handles.hpp"
#include "controller_interface/params.hpp"
#include "bus/endpoints.hpp"

namespace lcm_control::cm {

struct Time {
  int64_t utime = 0;  // hardware clock
  double seconds() const { return static_cast<double>(utime) * 1e-6; }
};

// A controller's numbers on `<name>/command`: one float64_t (width 1), or a float64_array_t of `width` values
// (array). `set` gets them checked (finite, the right count) from the bus, or straight from a command source in
// the loop, which hands the values over without encoding them.
struct CommandInput {
  bool array = false;
  size_t width = 1;
  std::function<void(const double* values)> set;
};

class ControllerContext;

class Controller {
 public:
  virtual ~Controller() = default;
  virtual void init(ControllerContext& ctx) = 0;
  virtual void starting(const Time& now) = 0;
  virtual void update(const Time& now, double period) = 0;
  virtual void stopping(const Time& now) { (void)now; }
  // From the current state after a hardware restart, resume or time jump.
  virtual void restart(const Time& now) {
    stopping(now);
    starting(now);
  }

  // The controller's own PIDs by joint, for run-time gains (pid_of for a PID per joint in `joints` order).
  virtual std::vector<std::string> pid_joints() const { return {}; }
  virtual Pid* pid(const std::string& joint) {
    (void)joint;
    return nullptr;
  }

  const Claim& claim() const { return claim_; }
  // The hardware components (indices in Hardware::components()) whose interfaces it commands, and those whose state
  // interfaces it only reads: leaving active stops the first, leaving inactive the second (ros2_control).
  struct ComponentUse {
    std::vector<int> commands, reads;
  };
  const ComponentUse& uses() const { return uses_; }
  int64_t dropped() const { return dropped_; }  // malformed or wrong-size commands
  // What it takes on `<name>/command` as numbers (ControllerContext::take_commands), or nullptr.
  const CommandInput* command_input() const { return input_.set ? &input_ : nullptr; }
  // Chaining (ROS 2): the reference interfaces it exports, and whether a running controller writes them now (chained
  // mode: its references come from there, not from its own `<name>/command`).
  const std::vector<JointData*>& exported() const { return exported_; }
  bool chained_mode() const { return chained_; }

 protected:
  // From update(): it cannot go on (ros2_control's return_type::ERROR). The loop stops it in this cycle and starts
  // its fallback_controllers; `reason` must outlive the controller (a string literal), and is logged once.
  void fail(const char* reason) { failure_ = reason ? reason : "failed"; }

  friend class ControllerContext;
  Claim claim_;
  ComponentUse uses_;
  CommandInput input_;
  int64_t dropped_ = 0;
  std::vector<JointData*> exported_;
  bool chained_ = false;  // set by the loop when a switch or a stop changes who writes its references
  bool running_ = false;  // set by the loop around starting()/stopping()
  const char* failure_ = nullptr;  // set by fail(), taken by the loop
  friend class Loop;
  friend class AsyncUpdate;
};

// What init() may use: its parameters, the robot, joint handles (claiming
// checks the transmission offers the interface), and LCM endpoints named
// `<controller>/...` under the namespace. The controller manager implements
// the handles' side (its hardware, cm::HardwareContext); a plugin's controller sees only this.
class ControllerContext {
 public:
  ControllerContext(std::string name, std::string type, Params& params, const RobotModel& model, Bus& bus,
                    Endpoints& endpoints)
      : name_(std::move(name)), type_(std::move(type)), params_(params), model_(model), bus_(bus), endpoints_(endpoints) {}
  virtual ~ControllerContext() = default;

  const std::string& name() const { return name_; }
  const std::string& type() const { return type_; }
  Params& params() { return params_; }
  const RobotModel& model() const { return model_; }

  // Claims `joint` on `iface`; throws ControllerError naming controller, joint,
  // interface needed and interfaces offered. `joint` may be a reference interface "<controller>/<dof>" another
  // controller exports (chaining): its exporter must be loaded (configured, when only checking).
  virtual JointData* claim(const std::string& joint, Interface iface) = 0;
  // Exports the reference interface "<this controller>/<dof>" on `interfaces` (the first is what a preceding
  // controller's command sets), showing the state of `state_from`: a preceding controller claims it as a joint.
  virtual JointData* export_reference(const std::string& dof, std::vector<Interface> interfaces,
                                      const JointData* state_from) = 0;
  // Claims a <gpio> command interface ("<gpio>/<interface>") / reads a <gpio> state interface; throws ControllerError
  // naming the parameter `key`, the interface and those the URDF's <gpio> blocks have.
  virtual GpioData* claim_gpio(const std::string& name, const std::string& key) = 0;
  virtual const std::vector<GpioData>& hardware_gpios() const = 0;
  virtual const GpioData* read_gpio(const std::string& name, const std::string& key) = 0;
  // Reads a joint without claiming it; the controller's joint list (cmctl list) shows it as `listed_as` when given
  // (a mimic joint computed from `joint`).
  virtual const JointData* read(const std::string& joint, const std::string& key, const std::string& listed_as = "") = 0;
  // A simulated sensor of `kind` (description/sensors.hpp) to read; throws ControllerError naming the parameter `key`,
  // why (no such sensor, another kind, not simulated) and the sensors of that kind there are.
  virtual const SensorData* sensor(const std::string& name, const std::string& key, SensorKind kind) = 0;
  std::vector<std::string> actuated_joints() const;

  std::string channel(const std::string& suffix) const { return bus_.channel(name_ + "/" + suffix); }
  std::string root_channel(const std::string& name) const { return bus_.channel(name); }
  Endpoints& endpoints() { return endpoints_; }
  Controller*& self() { return self_; }

  // Takes numbers on `<name>/command` (CommandInput: a float64_t, or with `array` a float64_array_t of `width`);
  // what is not finite or not `width` values is dropped, counted in dropped() and logged (the 1st and every 100th).
  void take_commands(bool array, size_t width, std::function<void(const double* values)> set);

  // Non-fatal findings shown to the user once at load.
  std::vector<std::string> notes;

 protected:
  // What the implementation records on the controller being initialised (self(); none when only checking types).
  void record_claim(const std::string& joint, Interface iface);  // a joint it commands on `iface`
  void record_read(const std::string& listed_as);                  // a joint it reads (listed while it claims none)
  void record_gpio(const std::string& name);                       // a <gpio> command interface it commands
  void record_use(int component, bool commands);                   // a hardware component it commands or reads
  void record_export(JointData* reference);                         // a reference interface it exports

  std::string name_, type_;
  Params& params_;
  const RobotModel& model_;
  Bus& bus_;
  Endpoints& endpoints_;
  Controller* self_ = nullptr;
};

// The PID of `joint` in `pids`, one per name of `joints` in the same order; nullptr for a joint not among them.
inline Pid* pid_of(const std::vector<std::string>& joints, std::vector<Pid>& pids, const std::string& joint) {
  for (size_t k = 0; k < joints.size() && k < pids.size(); ++k)
    if (joints[k] == joint) return &pids[k];
  return nullptr;
}

}  // namespace lcm_control::cm
