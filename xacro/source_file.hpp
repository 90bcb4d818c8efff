// Reading the files an expansion names (the input, its includes, YAML files): only a regular file is read, so an
// include naming a FIFO or a device is refused at once instead of waited on or read without end.
#pragma once

#include <string>

#include "xacro/process_error.hpp"

namespace lcm_control::xacro {

// What an optional include skips: the path names nothing.
class FileNotFound : public ProcessError {
 public:
  using ProcessError::ProcessError;
};

// The file's bytes. Throws FileNotFound when nothing is there, ProcessError for a folder, a FIFO, a device, a file
// larger than any robot description (64 MB) or a read error.
std::string read_source_file(const std::string& path);

}  // namespace lcm_control::xacro
