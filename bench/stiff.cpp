// bench_stiff: how stiff a D gain a light link takes at a 1 ms step, against
// the explicit bound. One revolute joint about its link's own axis (inertia I
// about it, nothing else moving, no gravity torque), spinning at 1 rad/s, damped
// by a D term only, for 1 s:
//  - explicit: the D term as an effort computed from the state before each
//    step and held over it, as a controller in controller_manager sends it
//    (effort interface); unstable above d*dt/I = 2 in any explicit scheme;
//  - implicit: the same D term as a position PID in the simulator (pid_gains
//    p 0, d), which sim_server applies through ImplicitJointDamper;
//  - effort with damping: the explicit effort sent with the damping it holds
//    (hardware_command_t::damping), as controller_manager's effort PIDs send
//    it; sim_server applies that part through ImplicitJointDamper too.
// "Stable" means the speed after 1 s is below the starting speed (a growing oscillation is above it). The largest stable explicit d is found by
// bisection; the implicit one is tried at the bound times 10, 100, ... up to 10^6.
//   bench_stiff [--smoke]
// Prints per inertia:
//   stiff INERTIA BOUND EXPLICIT_MAX IMPLICIT_MAX_TRIED IMPLICIT_STABLE(1|0) DAMPED_EFFORT_MAX_TRIED
//         DAMPED_EFFORT_STABLE(1|0)
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "sim_server/simulation.hpp"

namespace {

using namespace lcm_control;

constexpr double kDt = 1e-3;
constexpr int kSteps = 1000;

// A spinning link about z: mass 1 kg on the axis, izz = inertia; effort or position (with pid_gains p 0, d).
std::string write_robot(const std::string& dir, double inertia, bool effort, double d) {
  const std::string urdf = dir + (effort ? "/effort.urdf" : "/pid.urdf");
  const char* iface = effort ? "EffortJointInterface" : "PositionJointInterface";
  std::ofstream(urdf)
      << "<robot name=\"spinner\"><link name=\"world\"/>"
         "<joint name=\"fixed\" type=\"fixed\"><parent link=\"world\"/><child link=\"base\"/></joint>"
         "<link name=\"base\"><collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision>"
         "<inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/>"
         "</inertial></link>"
         "<joint name=\"spin\" type=\"continuous\"><parent link=\"base\"/><child link=\"rotor\"/>"
         "<origin xyz=\"0 0 0.1\"/><axis xyz=\"0 0 1\"/><limit effort=\"1e9\" velocity=\"1e6\"/></joint>"
         "<link name=\"rotor\"><collision><geometry><sphere radius=\"0.01\"/></geometry></collision>"
         "<inertial><mass value=\"1\"/><inertia ixx=\""
      << 2 * inertia << "\" ixy=\"0\" ixz=\"0\" iyy=\"" << 2 * inertia << "\" iyz=\"0\" izz=\"" << inertia
      << "\"/></inertial></link>"
         "<transmission name=\"t\"><type>transmission_interface/SimpleTransmission</type>"
         "<joint name=\"spin\"><hardwareInterface>hardware_interface/"
      << iface << "</hardwareInterface></joint><actuator name=\"m\"><mechanicalReduction>1</mechanicalReduction>"
      << "</actuator></transmission></robot>\n";
  const std::string yaml = dir + "/gains.yaml";
  std::ofstream(yaml) << "gazebo_ros_control:\n  pid_gains:\n    spin: {p: 0, i: 0, d: " << d << "}\n";
  return urdf;
}

enum class Damping { Explicit, SimulatorPid, EffortWithDamping };

// |v| after kSteps from 1 rad/s, damped by d as `how` says.
double final_speed(const std::string& dir, double inertia, double d, Damping how) {
  const bool explicit_d = how != Damping::SimulatorPid;
  const std::string urdf = write_robot(dir, inertia, explicit_d, d);
  sim::SimulationRates rates;
  rates.physics_hz = rates.control_hz = 1.0 / kDt;
  sim::Simulation sim(load_robot_model(urdf, explicit_d ? "" : dir + "/gains.yaml"), rates);
  sim::Actuators& act = sim.actuators();
  sim::Multibody& mb = sim.multibody();
  mb.set_state(mb.joints()[0].link, 0, 1.0);
  act.read(kDt);
  for (int k = 0; k < kSteps; ++k) {
    if (explicit_d)
      act.set_command(0, hardware_command_t::MODE_EFFORT, -d * act.joint_velocity(0),
                      how == Damping::EffortWithDamping ? d : 0.0);
    else  // p 0: only the D term of the PID to a goal at rest acts
      act.set_command(0, hardware_command_t::MODE_POSITION, 0.0);
    sim.step();
    if (!std::isfinite(act.joint_velocity(0)) || std::abs(act.joint_velocity(0)) > 1e6) return INFINITY;
  }
  return std::abs(act.joint_velocity(0));
}

}  // namespace

int main(int argc, char** argv) {
  const bool smoke = argc > 1 && std::strcmp(argv[1], "--smoke") == 0;
  char tmpl[] = "/tmp/bench_stiff_XXXXXX";
  if (!mkdtemp(tmpl)) return 1;
  const std::string dir = tmpl;
  const double inertias[] = {1e-4, 1e-3, 1e-2};
  int failures = 0;
  for (double inertia : inertias) {
    const double bound = 2 * inertia / kDt;
    double lo = 0, hi = 10 * bound;
    for (int k = 0; k < (smoke ? 4 : 30); ++k) {
      const double mid = 0.5 * (lo + hi);
      (final_speed(dir, inertia, mid, Damping::Explicit) < 1.0 ? lo : hi) = mid;
    }
    // The largest of 10, 100, ... 10^6 times the bound tried (up to the first unstable one), and whether all were
    // stable.
    auto implicit_up_to = [&](Damping how, double* tried) {
      bool stable = true;
      for (double f = 10; f <= (smoke ? 10 : 1e6) && stable; f *= 10) {
        *tried = f * bound;
        stable = final_speed(dir, inertia, *tried, how) < 1.0;
      }
      return stable;
    };
    double pid_tried = 0, effort_tried = 0;
    const bool pid_stable = implicit_up_to(Damping::SimulatorPid, &pid_tried);
    const bool effort_stable = implicit_up_to(Damping::EffortWithDamping, &effort_tried);
    failures += !pid_stable + !effort_stable;
    std::printf("stiff %g %g %g %g %d %g %d\n", inertia, bound, lo, pid_tried, pid_stable ? 1 : 0, effort_tried,
                effort_stable ? 1 : 0);
    if (smoke) break;
  }
  std::remove((dir + "/effort.urdf").c_str());
  std::remove((dir + "/pid.urdf").c_str());
  std::remove((dir + "/gains.yaml").c_str());
  rmdir(dir.c_str());
  return failures == 0 ? 0 : 1;
}
