#include "tools/lib/messages/message_json.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "bus/bus.hpp"
#include "lcm_control/visit.hpp"
#include "tools/lib/messages/message_text.hpp"

namespace lcm_control::tools {
namespace {

using Json = nlohmann::ordered_json;

template <class T>
Json scalar(const T& x) {
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(x)) return nullptr;
    return double(x);
  } else if constexpr (std::is_same_v<T, std::string>) {
    return x;
  } else {
    return int64_t(x);
  }
}

class ToJson {
 public:
  explicit ToJson(Json& out) : out_(out) {}
  template <class T>
  void value(const char* name, const T& x) {
    out_[name] = scalar(x);
  }
  void count(const char*, int32_t) {}
  template <class T>
  void list(const char* name, const std::vector<T>& xs, const char*) {
    Json a = Json::array();
    for (const auto& x : xs) a.push_back(scalar(x));
    out_[name] = std::move(a);
  }
  template <class T>
  void matrix(const char* name, const std::vector<std::vector<T>>& xs, const char*, int) {
    Json rows = Json::array();
    for (const auto& row : xs) {
      Json r = Json::array();
      for (const auto& x : row) r.push_back(scalar(x));
      rows.push_back(std::move(r));
    }
    out_[name] = std::move(rows);
  }
  template <class S>
  void structs(const char* name, const std::vector<S>& xs, const char*) {
    Json a = Json::array();
    for (const auto& x : xs) {
      Json o = Json::object();
      ToJson sub(o);
      visit(x, sub);
      a.push_back(std::move(o));
    }
    out_[name] = std::move(a);
  }
  template <class S>
  void nested(const char* name, const S& x) {
    Json o = Json::object();
    ToJson sub(o);
    visit(x, sub);
    out_[name] = std::move(o);
  }

 private:
  Json& out_;
};

// A JSON value as build_message's assignment text: numbers exactly, booleans as true/false, lists as [a,b].
std::string assignment_text(const std::string& path, const nlohmann::json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return std::to_string(v.get<int64_t>());
  if (v.is_number_unsigned()) return std::to_string(v.get<uint64_t>());
  if (v.is_number_float()) return fmt::format("{}", v.get<double>());
  if (v.is_array()) {
    std::string out = "[";
    for (size_t k = 0; k < v.size(); ++k) {
      if (v[k].is_array() || v[k].is_object() || v[k].is_null())
        throw std::invalid_argument(fmt::format("{}[{}]: expected a number, boolean or string", path, k));
      if (v[k].is_string() && v[k].get<std::string>().find_first_of(",[]") != std::string::npos)
        throw std::invalid_argument(fmt::format("{}[{}]: a string in a list cannot hold ',', '[' or ']'", path, k));
      out += (k ? "," : "") + assignment_text(path, v[k]);
    }
    return out + "]";
  }
  throw std::invalid_argument(fmt::format("{}: null is not a value", path));
}

// {"points": [{"positions": [..]}]} -> "points[0].positions=[..]"; a list of numbers stays one assignment.
void flatten(const std::string& path, const nlohmann::json& v, std::vector<std::string>& out) {
  if (v.is_object()) {
    for (const auto& [key, item] : v.items()) flatten(path.empty() ? key : path + "." + key, item, out);
    return;
  }
  if (v.is_array() && !v.empty() && (v.front().is_object() || v.front().is_array())) {
    for (size_t k = 0; k < v.size(); ++k) flatten(fmt::format("{}[{}]", path, k), v[k], out);
    return;
  }
  out.push_back(path + "=" + assignment_text(path, v));
}

}  // namespace

nlohmann::ordered_json message_to_json(const void* data, size_t size) {
  if (size < 8) throw std::runtime_error(fmt::format("{} bytes are too short for an LCM message", size));
  const int64_t hash = read_int64_be(data);
  Json out = Json::object();
  bool found = false;
  for_each_type([&](auto tag) {
    using Msg = typename decltype(tag)::type;
    if (found || hash != Msg::getHash()) return;
    found = true;
    Msg m{};
    if (!decode_guarded(m, data, size))
      throw std::runtime_error(fmt::format("the bytes do not decode as {}", Msg::getTypeName()));
    ToJson v(out);
    visit(static_cast<const Msg&>(m), v);
  });
  if (!found) throw std::runtime_error("not an lcm_control message (unknown fingerprint)");
  return out;
}

std::vector<uint8_t> message_from_json(const std::string& type, const nlohmann::json& fields, int64_t default_utime) {
  if (!fields.is_object())
    throw std::invalid_argument(fmt::format("{}: the fields must be a JSON object, got {}", type, fields.type_name()));
  std::vector<std::string> assignments;
  flatten("", fields, assignments);
  return build_message(type, assignments, default_utime);
}

nlohmann::ordered_json schema_json() {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const FieldInfo& f : kFieldInfo) {
    nlohmann::ordered_json field{{"type", f.lcm_type}};
    for (const auto& [key, text] : {std::pair{"count", f.count}, {"labels", f.labels}, {"unit", f.unit},
                                    {"nested", f.nested}, {"components", f.components}})
      if (*text) field[key] = text;
    out[f.type][f.field] = std::move(field);
  }
  return out;
}

}  // namespace lcm_control::tools
