// What a browser may ask of the dashboard, read from its JSON and checked before anything reaches the bus: publish
// a message, a controller-manager service, or an expression stream (like turret-cmd) on a command channel.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace lcm_control::dashboard {

// {"op": "publish", "channel": "j1_controller/command", "type": "float64_t", "msg": {"data": 0.5}}
struct Publish {
  std::string channel, type;
  nlohmann::json fields;
};
// {"op": "cm", "call": "list" | "load" | "unload" | "switch" | "reload", "names": [..], "start": [..], "stop": [..],
//  "strict": true}
struct CmCall {
  std::string call;
  std::vector<std::string> names, start, stop;
  bool strict = true;
};
// {"op": "expr", "channel": "j2_controller/command", "expressions": ["3.14*sin(i/100)"], "rate": 60}: float64_t
// for one expression, float64_array_t for several; {"op": "expr_stop", "channel": ...} ends it.
struct ExprStart {
  std::string channel;
  std::vector<std::string> expressions;
  double rate_hz = 60;
};
struct ExprStop {
  std::string channel;
};

struct Request {
  int64_t id = 0;  // echoed in the reply
  std::variant<Publish, CmCall, ExprStart, ExprStop> what;
  bool changes_robot() const;  // everything but a LIST or a gains query
};

// A request, or why it is refused (error != ""), with the id when one could be read.
struct Parsed {
  Request request;
  std::string error;
  bool ok() const { return error.empty(); }
};
Parsed parse_request(const std::string& text, bool read_only);

// The reply to request id: {"kind": "reply", "id": id, "ok": ok, "message": message}.
std::string reply_json(int64_t id, bool ok, const std::string& message);

// A frame's text as sent to browsers: invalid UTF-8 in a string is replaced, never thrown.
std::string dump(const nlohmann::json& j);
std::string dump(const nlohmann::ordered_json& j);

}  // namespace lcm_control::dashboard
