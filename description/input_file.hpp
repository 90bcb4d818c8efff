// Reading a file a user names on the command line (URDF, YAML, launch file):
// only a readable regular file is read (a folder, a FIFO or a device is
// refused at once, never waited on), and every failure is a ModelError naming
// the path and what to do.
#pragma once

#include <string>

namespace lcm_control {

// `what` names the file's role ("URDF", "config", "launch"); `flag` the option that gave it ("" if none).
std::string read_input_file(const std::string& path, const std::string& what, const std::string& flag = "");

}  // namespace lcm_control
