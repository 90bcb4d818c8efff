// SimpleTransmission (transmission_interface): one actuator drives one joint
// through a reduction n (n < 0 flips direction) and a joint offset.
// Joint values are what controllers see; actuator values travel on the wire.
#pragma once

namespace lcm_control {

struct SimpleTransmission {
  double reduction = 1.0;  // never 0 (validated at load)
  double offset = 0.0;     // joint units

  double actuator_to_joint_position(double xa) const { return xa / reduction + offset; }
  double actuator_to_joint_velocity(double va) const { return va / reduction; }
  double actuator_to_joint_effort(double ta) const { return ta * reduction; }

  double joint_to_actuator_position(double xj) const { return (xj - offset) * reduction; }
  double joint_to_actuator_velocity(double vj) const { return vj * reduction; }
  double joint_to_actuator_effort(double tj) const { return tj / reduction; }

  // A damping (effort per velocity: N*m*s/rad, N*s/m) between the two sides.
  double actuator_to_joint_damping(double da) const { return da * reduction * reduction; }
  double joint_to_actuator_damping(double dj) const { return dj / (reduction * reduction); }
};

}  // namespace lcm_control
