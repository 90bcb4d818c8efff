// sim_server: the URDF robot in Bullet, playing the hardware over LCM for a
// controller_manager (docs/hardware-protocol.md). Flags, then one call (sim_server/program.hpp).
#include "sim_server/program.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  CLI::App app{
      "Simulate a URDF robot in Bullet and play its hardware over LCM (hardware/state, hardware/command, clock, "
      "e_stop, sim_server/gains).\n"
      "Example: sim_server --urdf config/turret_bot.urdf --config config/turret_bot.yaml --mode lockstep",
      "sim_server"};
  sim::ProgramFlags flags;
  sim::add_program_flags(app, flags);
  return run_program(app, argc, argv, [&] { return sim::run_sim_server(flags); });
}
