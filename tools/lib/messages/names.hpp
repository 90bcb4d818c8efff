// Names and durations as users write and read them: ROS names without their leading '/', a channel name as an
// exact LCM subscription, seconds as text.
#pragma once

#include <string>

namespace lcm_control::tools {

// Seconds as text for messages: "2 s", "0.5 s".
std::string seconds_text(double s);

// `s` with LCM's regular-expression characters escaped: a subscription to exactly that channel.
std::string regex_escape(const std::string& s);

// A name as ROS users write it ("/j2_controller", "/j2_controller/command") without its leading '/'s.
std::string without_leading_slashes(std::string name);

}  // namespace lcm_control::tools
