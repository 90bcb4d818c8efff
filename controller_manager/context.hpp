// The controller manager's side of ControllerContext: claims and reads resolved against its Hardware (the joints of
// the transmissions and <ros2_control> blocks, the reference interfaces controllers export, <gpio>s and sensors).
#pragma once

#include <string>
#include <vector>

#include "controller_interface/controller.hpp"
#include "controller_interface/controller_type.hpp"
#include "controller_manager/hardware.hpp"

namespace lcm_control::cm {

class HardwareContext : public ControllerContext {
 public:
  // `info`: what the type declares (nullptr: nothing).
  HardwareContext(std::string name, std::string type, Params& params, const RobotModel& model, Hardware& hw, Bus& bus,
                  Endpoints& endpoints, const ControllerTypeInfo* info)
      : ControllerContext(std::move(name), std::move(type), params, model, bus, endpoints), hw_(hw), info_(info) {}

  JointData* claim(const std::string& joint, Interface iface) override;
  JointData* export_reference(const std::string& dof, std::vector<Interface> interfaces,
                              const JointData* state_from) override;
  GpioData* claim_gpio(const std::string& name, const std::string& key) override;
  const std::vector<GpioData>& hardware_gpios() const override { return hw_.gpios(); }
  const GpioData* read_gpio(const std::string& name, const std::string& key) override;
  const JointData* read(const std::string& joint, const std::string& key, const std::string& listed_as = "") override;
  const SensorData* sensor(const std::string& name, const std::string& key, SensorKind kind) override;
  // Loading checks that a reference interface's exporter is loaded; checking the configuration (doctor) only that it
  // is configured.
  void set_checking(bool checking) { checking_ = checking; }

 private:
  ControllerError not_a_gpio(const std::string& name, const std::string& key, const char* kind,
                             bool GpioData::*has) const;

  Hardware& hw_;
  const ControllerTypeInfo* info_;
  bool checking_ = false;
};

}  // namespace lcm_control::cm
