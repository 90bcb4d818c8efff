// xacro.load_yaml's reading of a YAML file into expression values, typed as PyYAML's safe_load types them (YAML 1.1:
// `1e-3` is a string, `1.0e-3` a float, yes/no/on/off are bools), with xacro's unit tags `!radians EXPR` and
// `!degrees EXPR` (an expression, converted to radians); every dict allows attribute access (xacro's
// YamlDictWrapper).
#pragma once

#include <string>

#include "xacro/python/value.hpp"

namespace lcm_control::xacro {

// Throws ProcessError (a file that cannot be read or parsed, a bad unit expression).
Value load_yaml_file(const std::string& path);
// The same for YAML text (tests).
Value load_yaml_text(const std::string& text);

}  // namespace lcm_control::xacro
