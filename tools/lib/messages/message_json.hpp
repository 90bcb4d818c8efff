// Any lcm_control message as JSON and back, through the schema (lcm_control/visit.hpp): what the dashboard streams
// to a browser and builds from what a browser sends.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lcm_control::tools {

// The payload's fields as a JSON object in schema order ({"utime": 5, "position": [0.1, 0.2], ...}); array lengths
// are left out, booleans are 0/1 (lcm-gen gives them as int8), a NaN or infinity is null. Throws std::runtime_error when the bytes are not
// one of our types or do not decode.
nlohmann::ordered_json message_to_json(const void* data, size_t size);

// The schema as the dashboard's page reads it: {"joint_state_t": {"position": {"type": "double", "count": "num_joints",
// "labels": "name", "unit": "rad or m"}, ...}, ...}, every message type and field in schema order (kFieldInfo); keys
// with nothing to say are left out.
nlohmann::ordered_json schema_json();

// Encodes a message of `type` (as build_message takes it) from a JSON object of its fields, nested as
// message_to_json writes them; fields not given are 0 or "", `utime` not given is default_utime. Throws
// std::invalid_argument naming the type and the field at fault.
std::vector<uint8_t> message_from_json(const std::string& type, const nlohmann::json& fields, int64_t default_utime);

}  // namespace lcm_control::tools
