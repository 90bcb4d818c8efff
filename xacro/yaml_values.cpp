// xacro.load_yaml: YAML to expression values with PyYAML safe_load's typing (see yaml_values.hpp).
#include "xacro/yaml_values.hpp"

#include "xacro/source_file.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <initializer_list>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <unordered_map>

#include "xacro/process_error.hpp"
#include "xacro/python/python_expr.hpp"

namespace lcm_control::xacro {

namespace {

class NoNames : public Names {
 public:
  std::optional<Value> lookup(const std::string&) const override { return std::nullopt; }
};

std::string without_underscores(const std::string& s) {
  std::string out;
  for (char c : s)
    if (c != '_') out += c;
  return out;
}

// PyYAML's YAML 1.1 implicit resolvers for a plain scalar, matched by hand (std::regex would cost more than the
// rest of an expansion): its bool, int and float patterns, alternative by alternative.
bool is_one_of(const std::string& s, std::initializer_list<const char*> words) {
  for (const char* w : words)
    if (s == w) return true;
  return false;
}

// s[i..] is at least one character, each in `chars`.
bool run_of(const std::string& s, size_t i, const char* chars) {
  return i < s.size() && s.find_first_not_of(chars, i) == std::string::npos;
}

const char* const kDigitsOrUnderscore = "0123456789_";

// [-+]?0b[0-1_]+ | [-+]?0[0-7_]+ | [-+]?(0|[1-9][0-9_]*) | [-+]?0x[0-9a-fA-F_]+ | [-+]?[1-9][0-9_]*(:[0-5]?[0-9])+
bool yaml_int(const std::string& s) {
  const size_t i = !s.empty() && (s[0] == '-' || s[0] == '+') ? 1 : 0;
  if (i >= s.size()) return false;
  if (s.compare(i, 2, "0b") == 0) return run_of(s, i + 2, "01_");
  if (s.compare(i, 2, "0x") == 0) return run_of(s, i + 2, "0123456789abcdefABCDEF_");
  if (s[i] == '0') return i + 1 == s.size() || run_of(s, i + 1, "01234567_");
  if (s[i] < '1' || s[i] > '9') return false;
  size_t j = s.find_first_not_of(kDigitsOrUnderscore, i + 1);
  if (j == std::string::npos) return true;
  if (s[j] != ':') return false;
  while (j < s.size()) {  // (:[0-5]?[0-9])+ to the end
    if (s[j] != ':') return false;
    const size_t k = s.find(':', j + 1), n = (k == std::string::npos ? s.size() : k) - j - 1;
    if (n == 1 ? !std::isdigit(static_cast<unsigned char>(s[j + 1]))
               : n != 2 || s[j + 1] < '0' || s[j + 1] > '5' || !std::isdigit(static_cast<unsigned char>(s[j + 2])))
      return false;
    j += n + 1;
  }
  return true;
}

// ([eE][-+][0-9]+)? up to the end, from i.
bool optional_exponent(const std::string& s, size_t i) {
  if (i == s.size()) return true;
  return (s[i] == 'e' || s[i] == 'E') && i + 1 < s.size() && (s[i + 1] == '-' || s[i + 1] == '+') &&
         run_of(s, i + 2, "0123456789");
}

// [-+]?[0-9][0-9_]*\.[0-9_]*([eE][-+][0-9]+)? | \.[0-9][0-9_]*([eE][-+][0-9]+)? |
// [-+]?[0-9][0-9_]*(:[0-5]?[0-9])+\.[0-9_]* | [-+]?\.(inf|Inf|INF) | \.(nan|NaN|NAN)
bool yaml_float(const std::string& s) {
  if (is_one_of(s, {".nan", ".NaN", ".NAN"})) return true;
  const size_t i = !s.empty() && (s[0] == '-' || s[0] == '+') ? 1 : 0;
  if (i >= s.size()) return false;
  if (is_one_of(s.substr(i), {".inf", ".Inf", ".INF"})) return true;
  if (s[i] == '.') {
    if (i != 0 || i + 1 >= s.size() || !std::isdigit(static_cast<unsigned char>(s[i + 1]))) return false;
    return optional_exponent(s, std::min(s.find_first_not_of(kDigitsOrUnderscore, i + 1), s.size()));
  }
  if (!std::isdigit(static_cast<unsigned char>(s[i]))) return false;
  size_t j = s.find_first_not_of(kDigitsOrUnderscore, i);
  if (j == std::string::npos) return false;
  if (s[j] == '.') return optional_exponent(s, std::min(s.find_first_not_of(kDigitsOrUnderscore, j + 1), s.size()));
  if (s[j] != ':') return false;
  const size_t dot = s.find('.', j);
  return dot != std::string::npos && yaml_int("1" + s.substr(j, dot - j)) &&
         (dot + 1 == s.size() || run_of(s, dot + 1, kDigitsOrUnderscore));
}

Value plain_scalar(const std::string& s) {
  if (s.empty() || s == "~" || s == "null" || s == "Null" || s == "NULL") return Value::none();
  const char c0 = s[0];
  if (is_one_of(s, {"yes", "Yes", "YES", "no", "No", "NO", "true", "True", "TRUE", "false", "False", "FALSE", "on",
                    "On", "ON", "off", "Off", "OFF"})) {
    const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(c0)));
    return Value::boolean(c == 'y' || c == 't' || (c == 'o' && (s[1] == 'n' || s[1] == 'N')));
  }
  if (std::string("-+0123456789.").find(c0) == std::string::npos) return Value::string(s);
  if (yaml_int(s)) {
    std::string v = without_underscores(s);
    int sign = 1;
    if (v[0] == '-' || v[0] == '+') {
      if (v[0] == '-') sign = -1;
      v = v.substr(1);
    }
    int64_t result = 0;
    if (v == "0") {
      result = 0;
    } else if (v.rfind("0b", 0) == 0) {
      result = std::stoll(v.substr(2), nullptr, 2);
    } else if (v.rfind("0x", 0) == 0) {
      result = std::stoll(v.substr(2), nullptr, 16);
    } else if (v[0] == '0') {
      result = std::stoll(v, nullptr, 8);
    } else if (v.find(':') != std::string::npos) {
      int64_t base = 1;
      std::vector<int64_t> digits;
      std::stringstream parts(v);
      std::string part;
      while (std::getline(parts, part, ':')) digits.push_back(std::stoll(part));
      for (auto it = digits.rbegin(); it != digits.rend(); ++it, base *= 60) result += *it * base;
    } else {
      try {
        result = std::stoll(v);
      } catch (const std::out_of_range&) {
        return Value::floating(sign * std::stod(v));
      }
    }
    return Value::integer(sign * result);
  }
  if (yaml_float(s)) {
    std::string v = without_underscores(s);
    for (char& c : v) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    double sign = 1;
    if (v[0] == '-' || v[0] == '+') {
      if (v[0] == '-') sign = -1;
      v = v.substr(1);
    }
    if (v == ".inf") return Value::floating(sign * std::numeric_limits<double>::infinity());
    if (v == ".nan") return Value::floating(std::numeric_limits<double>::quiet_NaN());
    if (v.find(':') != std::string::npos) {
      double base = 1, result = 0;
      std::vector<std::string> parts;
      std::stringstream ss(v);
      std::string part;
      while (std::getline(ss, part, ':')) parts.push_back(part);
      for (auto it = parts.rbegin(); it != parts.rend(); ++it, base *= 60) result += std::stod(*it) * base;
      return Value::floating(sign * result);
    }
    return Value::floating(sign * std::strtod(v.c_str(), nullptr));
  }
  return Value::string(s);
}

double unit_expression(const YAML::Node& node) {
  const std::string text = node.Scalar();
  try {
    return evaluate(text, NoNames()).as_double();
  } catch (const EvalError& e) {
    throw ProcessError(fmt::format("invalid expression: {} ({}, YAML line {})", text, e.what(), node.Mark().line + 1));
  }
}

// An alias (*a) is the anchored node itself in yaml-cpp's tree: converted once, by its place in the text, and shared
// as PyYAML shares it, so that an anchor bomb (each level aliasing the one before ten times) reads in linear time.
using Converted = std::unordered_map<size_t, Value>;
Value convert(const YAML::Node& node, Converted& done);

Value convert_collection(const YAML::Node& node, Converted& done) {
  const YAML::Mark mark = node.Mark();
  const bool known_place = mark.pos >= 0;
  const size_t key = size_t(mark.pos) * 2 + (node.IsMap() ? 1 : 0);
  if (known_place) {
    if (const auto it = done.find(key); it != done.end()) return it->second;
  }
  Value v;
  if (node.IsSequence()) {
    List items;
    items.reserve(node.size());
    for (const YAML::Node& item : node) items.push_back(convert(item, done));
    v = Value::list(std::move(items));
  } else {
    Dict d;
    d.attribute_access = true;
    for (const auto& kv : node) d.set(convert(kv.first, done), convert(kv.second, done));
    v = Value::dict(std::move(d));
  }
  if (known_place) done.emplace(key, v);
  return v;
}

Value convert(const YAML::Node& node, Converted& done) {
  switch (node.Type()) {
    case YAML::NodeType::Undefined:
    case YAML::NodeType::Null: return Value::none();
    case YAML::NodeType::Scalar: {
      const std::string& tag = node.Tag();
      if (tag == "!radians") return Value::floating(unit_expression(node));
      if (tag == "!degrees") return Value::floating(unit_expression(node) * (M_PI / 180.0));
      if (tag == "?") return plain_scalar(node.Scalar());
      if (tag == "tag:yaml.org,2002:int" || tag == "tag:yaml.org,2002:float" || tag == "tag:yaml.org,2002:bool" ||
          tag == "tag:yaml.org,2002:null") {
        Value v = plain_scalar(node.Scalar());
        if (tag == "tag:yaml.org,2002:float" && v.kind() == Value::Kind::Int)
          return Value::floating(static_cast<double>(v.as_int()));
        return v;
      }
      if (tag == "!" || tag == "tag:yaml.org,2002:str" || tag.empty()) return Value::string(node.Scalar());
      throw ProcessError(fmt::format("could not determine a constructor for the tag '{}' (YAML line {})", tag,
                                     node.Mark().line + 1));
    }
    case YAML::NodeType::Sequence:
    case YAML::NodeType::Map: return convert_collection(node, done);
  }
  return Value::none();
}

Value convert(const YAML::Node& node) {
  Converted done;
  return convert(node, done);
}

}  // namespace

Value load_yaml_text(const std::string& text) {
  try {
    return convert(YAML::Load(text));
  } catch (const YAML::Exception& e) {
    throw ProcessError(fmt::format("YAML error: {}", e.what()));
  }
}

Value load_yaml_file(const std::string& path) {
  const std::string text = read_source_file(path);
  try {
    return convert(YAML::Load(text));
  } catch (const YAML::Exception& e) {
    throw ProcessError(fmt::format("YAML error in {}: {}", path, e.what()));
  }
}

}  // namespace lcm_control::xacro
