#include "dashboard/requests.hpp"

#include <fmt/format.h>

#include <set>

namespace lcm_control::dashboard {
namespace {

using nlohmann::json;

constexpr size_t kMaxNameLength = 256;
constexpr size_t kMaxExpressions = 64;
constexpr double kMaxRateHz = 1000;

std::string text_at(const json& j, const char* key, bool required = true) {
  const auto it = j.find(key);
  if (it == j.end()) {
    if (required) throw std::invalid_argument(fmt::format("'{}' is missing", key));
    return "";
  }
  if (!it->is_string()) throw std::invalid_argument(fmt::format("'{}' must be a string", key));
  std::string s = it->get<std::string>();
  if (s.size() > kMaxNameLength) throw std::invalid_argument(fmt::format("'{}' is longer than {}", key, kMaxNameLength));
  return s;
}

std::string channel_at(const json& j) {
  std::string c = text_at(j, "channel");
  while (!c.empty() && c.front() == '/') c.erase(0, 1);  // ROS-style names work as in the other tools
  if (c.empty()) throw std::invalid_argument("'channel' is empty");
  for (unsigned char ch : c)
    if (ch < 0x21 || ch == 0x7f) throw std::invalid_argument("'channel' holds a space or control character");
  return c;
}

std::vector<std::string> names_at(const json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end()) return {};
  if (!it->is_array()) throw std::invalid_argument(fmt::format("'{}' must be a list of names", key));
  std::vector<std::string> out;
  for (const auto& v : *it) {
    if (!v.is_string() || v.get<std::string>().empty() || v.get<std::string>().size() > kMaxNameLength)
      throw std::invalid_argument(fmt::format("'{}' must be a list of names", key));
    out.push_back(v.get<std::string>());
  }
  return out;
}

}  // namespace

bool Request::changes_robot() const {
  if (const auto* c = std::get_if<CmCall>(&what)) return c->call != "list";
  if (const auto* p = std::get_if<Publish>(&what)) {
    if (p->type == "pid_gains_t" || p->type == "lcm_control.pid_gains_t") {
      const auto q = p->fields.find("query");
      return !(q != p->fields.end() && ((q->is_boolean() && q->get<bool>()) || (q->is_number() && q->get<double>() != 0)));
    }
  }
  return true;
}

Parsed parse_request(const std::string& text, bool read_only) {
  Parsed out;
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // a syntax error, or a number out of range ([1e400])
    out.error = fmt::format("not JSON: {}", e.what());
    return out;
  }
  if (!j.is_object()) {
    out.error = "a request is a JSON object with an 'op'";
    return out;
  }
  try {
    if (const auto id = j.find("id"); id != j.end()) {
      if (!id->is_number_integer()) throw std::invalid_argument("'id' must be an integer");
      out.request.id = id->get<int64_t>();
    }
    const std::string op = text_at(j, "op");
    if (op == "publish") {
      Publish p{channel_at(j), text_at(j, "type"), j.value("msg", json::object())};
      if (!p.fields.is_object()) throw std::invalid_argument("'msg' must be an object of the message's fields");
      out.request.what = std::move(p);
    } else if (op == "cm") {
      static const std::set<std::string> calls = {"list", "load", "unload", "switch", "reload"};
      CmCall c{text_at(j, "call"), names_at(j, "names"), names_at(j, "start"), names_at(j, "stop"), true};
      if (!calls.count(c.call))
        throw std::invalid_argument(fmt::format("unknown call '{}' (list, load, unload, switch, reload)", c.call));
      if (const auto s = j.find("strict"); s != j.end()) {
        if (!s->is_boolean()) throw std::invalid_argument("'strict' must be true or false");
        c.strict = s->get<bool>();
      }
      if ((c.call == "load" || c.call == "unload") && c.names.empty())
        throw std::invalid_argument(fmt::format("'{}' needs 'names'", c.call));
      if (c.call == "switch" && c.start.empty() && c.stop.empty())
        throw std::invalid_argument("'switch' needs 'start' or 'stop'");
      out.request.what = std::move(c);
    } else if (op == "expr") {
      ExprStart e{channel_at(j), names_at(j, "expressions"), 60};
      if (e.expressions.empty() || e.expressions.size() > kMaxExpressions)
        throw std::invalid_argument(fmt::format("'expressions' must hold 1 to {} expressions", kMaxExpressions));
      if (const auto r = j.find("rate"); r != j.end()) {
        if (!r->is_number() || !(r->get<double>() > 0) || r->get<double>() > kMaxRateHz)
          throw std::invalid_argument(fmt::format("'rate' must be a number of Hz above 0, at most {}", kMaxRateHz));
        e.rate_hz = r->get<double>();
      }
      out.request.what = std::move(e);
    } else if (op == "expr_stop") {
      out.request.what = ExprStop{channel_at(j)};
    } else {
      throw std::invalid_argument(fmt::format("unknown op '{}' (publish, cm, expr, expr_stop)", op));
    }
  } catch (const std::exception& e) {
    out.error = e.what();
    return out;
  }
  if (read_only && out.request.changes_robot())
    out.error = "the dashboard was started with --read-only: it shows the robot but sends no commands";
  return out;
}

std::string reply_json(int64_t id, bool ok, const std::string& message) {
  return dump(json{{"kind", "reply"}, {"id", id}, {"ok", ok}, {"message", message}});
}

std::string dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }
std::string dump(const nlohmann::ordered_json& j) {
  return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

}  // namespace lcm_control::dashboard
