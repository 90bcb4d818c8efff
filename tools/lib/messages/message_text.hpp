// Any lcm_control message as text and back, through the schema
// (lcm_control/visit.hpp): YAML-like text for `bus echo`, and a message built
// from field=value assignments for `bus pub`.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lcm_control::tools {

// "lcm_control.joint_state_t" for a payload's fingerprint, "" if it is not one of ours.
std::string type_of_payload(const void* data, size_t size);

// "lcm_control.joint_state_t", "joint_state_t" or "joint_state" -> "joint_state_t": the names the tools show and take.
std::string short_type_name(std::string type);

// Every message type, short names ("joint_state_t"), sorted.
std::vector<std::string> message_type_names();

// The payload as YAML-like lines ("utime: 5", "position: [0.1, 0.2]", nested
// messages as "- " items); array lengths are left out. Throws std::runtime_error
// when the bytes are not one of our types or do not decode.
std::string message_yaml(const void* data, size_t size);

// Encodes a message of `type` ("joint_state_t", "lcm_control.joint_state_t" or
// "joint_state") from assignments such as "data=0.5", "position[1]=2",
// "name=[j1,j2]", "points[0].positions=[0.1,0.2]". Unset fields are 0 or "";
// array lengths follow the arrays (arrays sized by one count must agree);
// `utime`, if the type has it and it is not assigned, is default_utime.
// Throws std::invalid_argument naming the type and the field at fault, with the
// type's fields.
std::vector<uint8_t> build_message(const std::string& type, const std::vector<std::string>& assignments,
                                   int64_t default_utime);

// The type's fields as assignable paths with their kind ("utime (int64)", "name[] (string)").
std::vector<std::string> message_fields(const std::string& type);

}  // namespace lcm_control::tools
