// The built-ins of xacro's expressions: Python's functions and types, `math` (bare and as math.), the `python`
// namespace, the methods of str, list and dict, and format()/'%' formatting.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

#include "description/xacro/python_eval.hpp"
#include "description/xacro/python_literals.hpp"

namespace lcm_control::xacro::py {

namespace {

using Fn = std::function<Value(const List&, const Kwargs&)>;
using Kind = Value::Kind;

bool is_intlike(const Value& v) { return v.kind() == Kind::Int || v.kind() == Kind::Bool; }

void arity(const char* name, const List& args, size_t min, size_t max) {
  if (args.size() >= min && args.size() <= max) return;
  if (min == max)
    raise("TypeError", fmt::format("{}() takes exactly {} argument{} ({} given)", name, min, min == 1 ? "" : "s",
                                   args.size()));
  if (args.size() < min)
    raise("TypeError", fmt::format("{}() takes at least {} argument{} ({} given)", name, min, min == 1 ? "" : "s",
                                   args.size()));
  raise("TypeError", fmt::format("{}() takes at most {} argument{} ({} given)", name, max, max == 1 ? "" : "s",
                                 args.size()));
}

void no_kwargs(const char* name, const Kwargs& kwargs) {
  if (!kwargs.empty()) raise("TypeError", fmt::format("{}() takes no keyword arguments", name));
}

const Value* kwarg(const Kwargs& kwargs, const char* name) {
  for (const auto& [k, v] : kwargs)
    if (k == name) return &v;
  return nullptr;
}

void only_kwargs(const char* fn, const Kwargs& kwargs, std::initializer_list<const char*> allowed) {
  for (const auto& kv : kwargs)
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return kv.first == a; }))
      raise("TypeError", fmt::format("{}() got an unexpected keyword argument '{}'", fn, kv.first));
}

double number(const char* fn, const Value& v) {
  if (!v.is_number()) raise("TypeError", fmt::format("must be real number, not {}", v.type_name()));
  (void)fn;
  return v.as_double();
}

int64_t integer(const char* fn, const Value& v) {
  if (!is_intlike(v))
    raise("TypeError", fmt::format("'{}' object cannot be interpreted as an integer", v.type_name()));
  (void)fn;
  return v.as_int();
}

int64_t float_to_int(double d) {
  if (std::isinf(d)) raise("OverflowError", "cannot convert float infinity to integer");
  if (std::isnan(d)) raise("ValueError", "cannot convert float NaN to integer");
  if (d >= 9223372036854775808.0 || d < -9223372036854775808.0)
    raise("OverflowError", "integer result does not fit in 64 bits");
  return static_cast<int64_t>(d);
}

// Python's int()/float() accept single underscores between digits: "1_000".
std::optional<std::string> without_digit_underscores(const std::string& s) {
  if (s.find('_') == std::string::npos) return s;
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '_') {
      out += s[i];
      continue;
    }
    const bool between = i > 0 && i + 1 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i - 1])) &&
                         std::isxdigit(static_cast<unsigned char>(s[i + 1]));
    if (!between) return std::nullopt;
  }
  return out;
}

// ---- format() ---------------------------------------------------------------------------------------------------

struct Spec {
  char fill = ' ';
  char align = 0;
  char sign = '-';
  bool alternate = false;
  size_t width = 0;
  char grouping = 0;
  int precision = -1;
  char type = 0;
};

Spec parse_spec(std::string_view s) {
  Spec spec;
  size_t i = 0;
  auto is_align = [](char c) { return c == '<' || c == '>' || c == '^' || c == '='; };
  if (s.size() >= 2 && is_align(s[1])) {
    spec.fill = s[0];
    spec.align = s[1];
    i = 2;
  } else if (!s.empty() && is_align(s[0])) {
    spec.align = s[0];
    i = 1;
  }
  if (i < s.size() && (s[i] == '+' || s[i] == '-' || s[i] == ' ')) spec.sign = s[i++];
  if (i < s.size() && s[i] == 'z') ++i;
  if (i < s.size() && s[i] == '#') {
    spec.alternate = true;
    ++i;
  }
  if (i < s.size() && s[i] == '0') {
    if (!spec.align) {
      spec.fill = '0';
      spec.align = '=';
    }
    ++i;
  }
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) spec.width = spec.width * 10 + (s[i++] - '0');
  if (i < s.size() && (s[i] == ',' || s[i] == '_')) spec.grouping = s[i++];
  if (i < s.size() && s[i] == '.') {
    ++i;
    if (i >= s.size() || !std::isdigit(static_cast<unsigned char>(s[i]))) raise("ValueError", "Format specifier missing precision");
    spec.precision = 0;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) spec.precision = spec.precision * 10 + (s[i++] - '0');
  }
  if (i < s.size()) spec.type = s[i++];
  if (i < s.size()) raise("ValueError", "Invalid format specifier");
  return spec;
}

std::string group_digits(const std::string& digits, char sep) {
  std::string out;
  const size_t n = digits.size();
  for (size_t i = 0; i < n; ++i) {
    if (i > 0 && (n - i) % 3 == 0) out += sep;
    out += digits[i];
  }
  return out;
}

std::string pad(std::string sign, std::string body, const Spec& spec, char default_align) {
  const char align = spec.align ? spec.align : default_align;
  const size_t len = sign.size() + body.size();
  if (len >= spec.width) return sign + body;
  const size_t fill = spec.width - len;
  const std::string f(fill, spec.fill);
  switch (align) {
    case '<': return sign + body + f;
    case '^': return std::string(fill / 2, spec.fill) + sign + body + std::string(fill - fill / 2, spec.fill);
    case '=': return sign + f + body;
    default: return f + sign + body;
  }
}

std::string sign_of(bool negative, const Spec& spec) {
  if (negative) return "-";
  if (spec.sign == '+') return "+";
  if (spec.sign == ' ') return " ";
  return "";
}

std::string format_float(double d, Spec spec) {
  const bool negative = std::signbit(d) && !std::isnan(d);
  const double a = std::fabs(d);
  std::string body;
  char type = spec.type;
  const bool upper = type == 'E' || type == 'F' || type == 'G';
  if (std::isinf(a) || std::isnan(a)) {
    body = std::isinf(a) ? "inf" : "nan";
    if (upper) std::transform(body.begin(), body.end(), body.begin(), ::toupper);
    if (type == '%') body += '%';
  } else if (type == 0 && spec.precision < 0) {
    body = float_repr(a);
  } else {
    double x = a;
    if (type == '%') x *= 100;
    const int p = spec.precision < 0 ? 6 : spec.precision;
    char conv = type == 0 ? 'g' : type == '%' ? 'f' : type == 'n' ? 'g' : type;
    if (type == 0 && p == 0) conv = 'g';
    char fmtbuf[16];
    std::snprintf(fmtbuf, sizeof fmtbuf, "%%%s.%d%c", spec.alternate ? "#" : "", type == 0 && p == 0 ? 1 : p, conv);
    char buf[512];
    std::snprintf(buf, sizeof buf, fmtbuf, x);
    body = buf;
    if (type == 0 && body.find_first_of(".e") == std::string::npos) body += ".0";
    if (type == '%') body += '%';
  }
  if (spec.grouping && std::isfinite(a)) {
    const size_t end = body.find_first_not_of("0123456789");
    body = group_digits(body.substr(0, end), spec.grouping) + (end == std::string::npos ? "" : body.substr(end));
  }
  if (spec.fill == '0' && spec.align == '=' && spec.grouping) {
    // zero padding with grouping is rare; pad plainly
  }
  return pad(sign_of(negative, spec), body, spec, '>');
}

std::string format_int(int64_t i, const Spec& spec) {
  const bool negative = i < 0;
  const uint64_t a = negative ? 0 - static_cast<uint64_t>(i) : static_cast<uint64_t>(i);
  std::string body, prefix;
  switch (spec.type) {
    case 'x': body = fmt::format("{:x}", a); prefix = "0x"; break;
    case 'X': body = fmt::format("{:X}", a); prefix = "0X"; break;
    case 'o': body = fmt::format("{:o}", a); prefix = "0o"; break;
    case 'b': body = fmt::format("{:b}", a); prefix = "0b"; break;
    case 'c': body = std::string(1, static_cast<char>(a)); break;
    default: body = std::to_string(a);
  }
  if (spec.grouping) body = group_digits(body, spec.grouping);
  if (spec.alternate) body = prefix + body;
  return pad(sign_of(negative, spec), body, spec, '>');
}

// ---- str methods ------------------------------------------------------------------------------------------------

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

const std::string& str_arg(const char* method, const Value& v) {
  if (v.kind() != Kind::Str)
    raise("TypeError", fmt::format("{}() argument must be str, not {}", method, v.type_name()));
  return v.as_str();
}

List split(const std::string& s, const Value* sep, int64_t maxsplit) {
  List out;
  if (!sep || sep->is_none()) {
    size_t i = 0;
    while (true) {
      while (i < s.size() && is_space(s[i])) ++i;
      if (i >= s.size()) break;
      if (maxsplit >= 0 && static_cast<int64_t>(out.size()) == maxsplit) {
        size_t end = s.size();
        while (end > i && is_space(s[end - 1])) --end;
        out.push_back(Value::string(s.substr(i, end - i)));
        break;
      }
      size_t j = i;
      while (j < s.size() && !is_space(s[j])) ++j;
      out.push_back(Value::string(s.substr(i, j - i)));
      i = j;
    }
    return out;
  }
  const std::string& d = str_arg("split", *sep);
  if (d.empty()) raise("ValueError", "empty separator");
  size_t i = 0;
  while (true) {
    const size_t j = s.find(d, i);
    if (j == std::string::npos || (maxsplit >= 0 && static_cast<int64_t>(out.size()) == maxsplit)) {
      out.push_back(Value::string(s.substr(i)));
      return out;
    }
    out.push_back(Value::string(s.substr(i, j - i)));
    i = j + d.size();
  }
}

std::string strip(const std::string& s, const List& args, bool left, bool right) {
  auto drop = [&](char c) {
    if (args.empty() || args[0].is_none()) return is_space(c);
    return args[0].as_str().find(c) != std::string::npos;
  };
  size_t b = 0, e = s.size();
  if (left)
    while (b < e && drop(s[b])) ++b;
  if (right)
    while (e > b && drop(s[e - 1])) --e;
  return s.substr(b, e - b);
}

bool affix(const std::string& s, const List& args, bool prefix, const char* name) {
  arity(name, args, 1, 3);
  int64_t size = static_cast<int64_t>(s.size());
  auto clamp = [&](int64_t i) { return std::clamp<int64_t>(i < 0 ? i + size : i, 0, size); };
  const int64_t start = args.size() > 1 && !args[1].is_none() ? clamp(integer(name, args[1])) : 0;
  const int64_t end = args.size() > 2 && !args[2].is_none() ? clamp(integer(name, args[2])) : size;
  const std::string sub = end > start ? s.substr(static_cast<size_t>(start), static_cast<size_t>(end - start)) : "";
  List candidates;
  if (args[0].kind() == Kind::Tuple)
    candidates = args[0].as_list();
  else if (args[0].kind() == Kind::Str)
    candidates.push_back(args[0]);
  else
    raise("TypeError", fmt::format("{} first arg must be str or a tuple of str, not {}", name, args[0].type_name()));
  for (const Value& c : candidates) {
    const std::string& a = str_arg(name, c);
    if (a.size() > sub.size()) continue;
    if (prefix ? sub.compare(0, a.size(), a) == 0 : sub.compare(sub.size() - a.size(), a.size(), a) == 0)
      return true;
  }
  return false;
}

size_t count_occurrences(const std::string& s, const std::string& sub) {
  if (sub.empty()) return s.size() + 1;
  size_t n = 0;
  for (size_t i = s.find(sub); i != std::string::npos; i = s.find(sub, i + sub.size())) ++n;
  return n;
}

Value format_field(const std::string& field, const List& args, const Kwargs& kwargs, size_t& auto_index,
                   int& numbering) {
  size_t end = field.find_first_of(".[");
  const std::string head = field.substr(0, end);
  Value v;
  if (head.empty() || std::all_of(head.begin(), head.end(), ::isdigit)) {
    size_t idx;
    if (head.empty()) {
      if (numbering == 2) raise("ValueError", "cannot switch from manual field specification to automatic field numbering");
      numbering = 1;
      idx = auto_index++;
    } else {
      if (numbering == 1) raise("ValueError", "cannot switch from automatic field numbering to manual field specification");
      numbering = 2;
      idx = std::stoul(head);
    }
    if (idx >= args.size())
      raise("IndexError", fmt::format("Replacement index {} out of range for positional args tuple", idx));
    v = args[idx];
  } else {
    const Value* kw = kwarg(kwargs, head.c_str());
    if (!kw) raise("KeyError", repr(Value::string(head)));
    v = *kw;
  }
  while (end != std::string::npos) {
    if (field[end] == '.') {
      const size_t next = field.find_first_of(".[", end + 1);
      v = attribute(v, field.substr(end + 1, next == std::string::npos ? std::string::npos : next - end - 1));
      end = next;
    } else {
      const size_t close = field.find(']', end);
      if (close == std::string::npos) raise("ValueError", "Missing ']' in format string");
      const std::string key = field.substr(end + 1, close - end - 1);
      const bool numeric = !key.empty() && std::all_of(key.begin(), key.end(), ::isdigit);
      v = index(v, numeric ? Value::integer(std::stoll(key)) : Value::string(key));
      end = close + 1 < field.size() ? close + 1 : std::string::npos;
    }
  }
  return v;
}

std::string str_format(const std::string& f, const List& args, const Kwargs& kwargs) {
  std::string out;
  size_t auto_index = 0;
  int numbering = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    const char c = f[i];
    if (c == '}') {
      if (i + 1 < f.size() && f[i + 1] == '}') {
        out += '}';
        ++i;
        continue;
      }
      raise("ValueError", "Single '}' encountered in format string");
    }
    if (c != '{') {
      out += c;
      continue;
    }
    if (i + 1 < f.size() && f[i + 1] == '{') {
      out += '{';
      ++i;
      continue;
    }
    int depth = 1;
    size_t j = i + 1;
    for (; j < f.size() && depth > 0; ++j) {
      if (f[j] == '{') ++depth;
      if (f[j] == '}') --depth;
    }
    if (depth > 0) raise("ValueError", "expected '}' before end of string");
    const std::string inner = f.substr(i + 1, j - i - 2);
    size_t colon = std::string::npos, bang = std::string::npos;
    for (size_t k = 0, brackets = 0; k < inner.size(); ++k) {
      if (inner[k] == '[') ++brackets;
      if (inner[k] == ']' && brackets) --brackets;
      if (brackets) continue;
      if (inner[k] == '!' && bang == std::string::npos && colon == std::string::npos) bang = k;
      if (inner[k] == ':') {
        colon = k;
        break;
      }
    }
    const std::string field = inner.substr(0, std::min(bang, colon));
    std::string spec = colon == std::string::npos ? "" : inner.substr(colon + 1);
    if (spec.find('{') != std::string::npos) spec = str_format(spec, args, kwargs);
    Value v = format_field(field, args, kwargs, auto_index, numbering);
    if (bang != std::string::npos) {
      const char conv = bang + 1 < inner.size() ? inner[bang + 1] : 0;
      if (conv == 'r' || conv == 'a')
        v = Value::string(repr(v));
      else if (conv == 's')
        v = Value::string(str(v));
      else
        raise("ValueError", "Unknown conversion specifier");
    }
    out += format_value(v, spec);
    i = j - 1;
  }
  return out;
}

Value bound(const Value& self, const char* name, std::function<Value(const Value&, const List&, const Kwargs&)> fn) {
  return Value::callable(fmt::format("{}.{}", self.type_name(), name),
                         [self, fn = std::move(fn)](const List& args, const Kwargs& kwargs) {
                           return fn(self, args, kwargs);
                         });
}

std::optional<Value> str_method(const Value& self, const std::string& name) {
  using Args = const List&;
  using Kw = const Kwargs&;
  const char* n = name.c_str();
  auto simple = [&](auto fn) -> std::optional<Value> {
    return bound(self, n, [fn, n](const Value& s, Args args, Kw kwargs) -> Value {
      no_kwargs(n, kwargs);
      return fn(s.as_str(), args);
    });
  };
  if (name == "split" || name == "rsplit") {
    const bool right = name == "rsplit";
    return bound(self, n, [right](const Value& s, Args args, Kw kwargs) {
      only_kwargs(right ? "rsplit" : "split", kwargs, {"sep", "maxsplit"});
      arity(right ? "rsplit" : "split", args, 0, 2);
      const Value* sep = args.size() > 0 ? &args[0] : kwarg(kwargs, "sep");
      const Value* max = args.size() > 1 ? &args[1] : kwarg(kwargs, "maxsplit");
      const int64_t maxsplit = max ? integer("split", *max) : -1;
      if (!right || maxsplit < 0) return Value::list(split(s.as_str(), sep, maxsplit));
      std::string r(s.as_str().rbegin(), s.as_str().rend());
      std::optional<Value> rsep;
      if (sep && !sep->is_none()) rsep = Value::string(std::string(sep->as_str().rbegin(), sep->as_str().rend()));
      List parts = split(r, rsep ? &*rsep : nullptr, maxsplit);
      List out;
      for (auto it = parts.rbegin(); it != parts.rend(); ++it)
        out.push_back(Value::string(std::string(it->as_str().rbegin(), it->as_str().rend())));
      return Value::list(std::move(out));
    });
  }
  if (name == "join")
    return simple([](const std::string& s, Args args) {
      arity("join", args, 1, 1);
      std::string out;
      const List items = iterate(args[0]);
      for (size_t i = 0; i < items.size(); ++i) {
        if (items[i].kind() != Kind::Str)
          raise("TypeError",
                fmt::format("sequence item {}: expected str instance, {} found", i, items[i].type_name()));
        if (i) out += s;
        out += items[i].as_str();
      }
      return Value::string(std::move(out));
    });
  if (name == "upper" || name == "lower") {
    const bool up = name == "upper";
    return simple([up](const std::string& s, Args args) {
      arity(up ? "upper" : "lower", args, 0, 0);
      std::string out = s;
      for (char& c : out) c = static_cast<char>(up ? std::toupper(static_cast<unsigned char>(c)) : std::tolower(static_cast<unsigned char>(c)));
      return Value::string(std::move(out));
    });
  }
  if (name == "title" || name == "capitalize") {
    const bool title = name == "title";
    return simple([title](const std::string& s, Args args) {
      arity(title ? "title" : "capitalize", args, 0, 0);
      std::string out = s;
      bool start = true;
      for (char& c : out) {
        const unsigned char u = static_cast<unsigned char>(c);
        c = static_cast<char>(start ? std::toupper(u) : std::tolower(u));
        start = title ? !std::isalpha(static_cast<unsigned char>(c)) : false;
      }
      return Value::string(std::move(out));
    });
  }
  if (name == "replace")
    return simple([](const std::string& s, Args args) {
      arity("replace", args, 2, 3);
      const std::string& from = str_arg("replace", args[0]);
      const std::string& to = str_arg("replace", args[1]);
      int64_t limit = args.size() > 2 ? integer("replace", args[2]) : -1;
      std::string out;
      size_t i = 0;
      if (from.empty()) {
        for (size_t k = 0; k <= s.size(); ++k) {
          if (limit != 0) {
            out += to;
            --limit;
          }
          if (k < s.size()) out += s[k];
        }
        return Value::string(std::move(out));
      }
      for (size_t j; limit != 0 && (j = s.find(from, i)) != std::string::npos; --limit) {
        out += s.substr(i, j - i) + to;
        i = j + from.size();
      }
      return Value::string(out + s.substr(i));
    });
  if (name == "startswith" || name == "endswith") {
    const bool prefix = name == "startswith";
    return simple([prefix](const std::string& s, Args args) {
      return Value::boolean(affix(s, args, prefix, prefix ? "startswith" : "endswith"));
    });
  }
  if (name == "strip" || name == "lstrip" || name == "rstrip") {
    const bool left = name != "rstrip", right = name != "lstrip";
    return simple([left, right](const std::string& s, Args args) {
      arity("strip", args, 0, 1);
      return Value::string(strip(s, args, left, right));
    });
  }
  if (name == "find" || name == "rfind" || name == "index" || name == "rindex" || name == "count") {
    const std::string which = name;
    return simple([which](const std::string& s, Args args) {
      arity(which.c_str(), args, 1, 3);
      const std::string& sub = str_arg(which.c_str(), args[0]);
      const int64_t size = static_cast<int64_t>(s.size());
      auto clamp = [&](int64_t i) { return std::clamp<int64_t>(i < 0 ? i + size : i, 0, size); };
      const size_t start = static_cast<size_t>(args.size() > 1 ? clamp(integer(which.c_str(), args[1])) : 0);
      const size_t end = static_cast<size_t>(args.size() > 2 ? clamp(integer(which.c_str(), args[2])) : size);
      const std::string part = end > start ? s.substr(start, end - start) : "";
      if (which == "count") return Value::integer(static_cast<int64_t>(count_occurrences(part, sub)));
      const size_t at = which[0] == 'r' ? part.rfind(sub) : part.find(sub);
      if (at == std::string::npos) {
        if (which == "index" || which == "rindex") raise("ValueError", "substring not found");
        if (end < start && !sub.empty()) return Value::integer(-1);
        return Value::integer(-1);
      }
      return Value::integer(static_cast<int64_t>(at + start));
    });
  }
  if (name == "format")
    return bound(self, n, [](const Value& s, Args args, Kw kwargs) {
      return Value::string(str_format(s.as_str(), args, kwargs));
    });
  if (name == "zfill")
    return simple([](const std::string& s, Args args) {
      arity("zfill", args, 1, 1);
      const int64_t width = integer("zfill", args[0]);
      if (static_cast<int64_t>(s.size()) >= width) return Value::string(s);
      const size_t fill = static_cast<size_t>(width) - s.size();
      if (!s.empty() && (s[0] == '-' || s[0] == '+')) return Value::string(s[0] + std::string(fill, '0') + s.substr(1));
      return Value::string(std::string(fill, '0') + s);
    });
  if (name == "isdigit" || name == "isalpha" || name == "isalnum" || name == "isspace" || name == "isupper" ||
      name == "islower") {
    const std::string which = name;
    return simple([which](const std::string& s, Args args) {
      arity(which.c_str(), args, 0, 0);
      if (s.empty()) return Value::boolean(false);
      auto all = [&](int (*pred)(int)) {
        return std::all_of(s.begin(), s.end(), [pred](char c) { return pred(static_cast<unsigned char>(c)) != 0; });
      };
      if (which == "isdigit") return Value::boolean(all(::isdigit));
      if (which == "isalpha") return Value::boolean(all(::isalpha));
      if (which == "isalnum") return Value::boolean(all(::isalnum));
      if (which == "isspace") return Value::boolean(all(::isspace));
      const bool upper = which == "isupper";
      bool cased = false;
      for (char c : s) {
        const unsigned char u = static_cast<unsigned char>(c);
        if (upper ? std::islower(u) : std::isupper(u)) return Value::boolean(false);
        cased = cased || std::isalpha(u);
      }
      return Value::boolean(cased);
    });
  }
  if (name == "splitlines")
    return simple([](const std::string& s, Args args) {
      arity("splitlines", args, 0, 0);
      List out;
      size_t i = 0;
      while (i < s.size()) {
        size_t j = s.find_first_of("\r\n", i);
        if (j == std::string::npos) j = s.size();
        out.push_back(Value::string(s.substr(i, j - i)));
        i = j + ((j + 1 < s.size() && s[j] == '\r' && s[j + 1] == '\n') ? 2 : 1);
      }
      return Value::list(std::move(out));
    });
  return std::nullopt;
}

std::optional<Value> sequence_method(const Value& self, const std::string& name) {
  if (name == "index")
    return bound(self, "index", [](const Value& s, const List& args, const Kwargs& kwargs) {
      no_kwargs("index", kwargs);
      arity("index", args, 1, 1);
      const List& items = s.as_list();
      for (size_t i = 0; i < items.size(); ++i)
        if (equal(items[i], args[0])) return Value::integer(static_cast<int64_t>(i));
      if (s.kind() == Kind::Tuple) raise("ValueError", "tuple.index(x): x not in tuple");
      raise("ValueError", fmt::format("{} is not in list", repr(args[0])));
    });
  if (name == "count")
    return bound(self, "count", [](const Value& s, const List& args, const Kwargs& kwargs) {
      no_kwargs("count", kwargs);
      arity("count", args, 1, 1);
      const List& items = s.as_list();
      return Value::integer(std::count_if(items.begin(), items.end(), [&](const Value& v) { return equal(v, args[0]); }));
    });
  if (name == "copy" && self.kind() == Kind::List)
    return bound(self, "copy", [](const Value& s, const List&, const Kwargs&) { return Value::list(s.as_list()); });
  return std::nullopt;
}

std::optional<Value> dict_method(const Value& self, const std::string& name) {
  if (name == "get")
    return bound(self, "get", [](const Value& s, const List& args, const Kwargs& kwargs) {
      no_kwargs("get", kwargs);
      arity("get", args, 1, 2);
      if (const Value* v = s.as_dict().find(args[0])) return *v;
      return args.size() > 1 ? args[1] : Value::none();
    });
  if (name == "keys" || name == "values" || name == "items") {
    const int which = name == "keys" ? 0 : name == "values" ? 1 : 2;
    return bound(self, name.c_str(), [which](const Value& s, const List& args, const Kwargs& kwargs) {
      no_kwargs("keys", kwargs);
      arity(which == 0 ? "keys" : which == 1 ? "values" : "items", args, 0, 0);
      List out;
      for (const auto& [k, v] : s.as_dict().items)
        out.push_back(which == 0 ? k : which == 1 ? v : Value::tuple({k, v}));
      return Value::list(std::move(out));
    });
  }
  if (name == "copy")
    return bound(self, "copy", [](const Value& s, const List&, const Kwargs&) { return Value::dict(s.as_dict()); });
  return std::nullopt;
}

// ---- built-in functions -----------------------------------------------------------------------------------------

List args_or_iterable(const char* name, const List& args) {
  if (args.empty()) raise("TypeError", fmt::format("{} expected at least 1 argument, got 0", name));
  return args.size() == 1 ? iterate(args[0]) : args;
}

Value min_max(const char* name, bool is_max, const List& args, const Kwargs& kwargs) {
  only_kwargs(name, kwargs, {"key", "default"});
  const List items = args_or_iterable(name, args);
  const Value* key = kwarg(kwargs, "key");
  if (items.empty()) {
    if (const Value* d = kwarg(kwargs, "default")) return *d;
    raise("ValueError", fmt::format("{}() arg is an empty sequence", name));
  }
  size_t best = 0;
  Value best_key = key && !key->is_none() ? call(*key, {items[0]}) : items[0];
  for (size_t i = 1; i < items.size(); ++i) {
    Value k = key && !key->is_none() ? call(*key, {items[i]}) : items[i];
    if (compare(is_max ? ast::Cmp::Gt : ast::Cmp::Lt, k, best_key)) {
      best = i;
      best_key = std::move(k);
    }
  }
  return items[best];
}

Value round_builtin(const List& args, const Kwargs& kwargs) {
  only_kwargs("round", kwargs, {"ndigits"});
  arity("round", args, 1, 2);
  const Value* nd = args.size() > 1 ? &args[1] : kwarg(kwargs, "ndigits");
  const Value& x = args[0];
  if (!x.is_number()) raise("TypeError", fmt::format("type {} doesn't define __round__ method", x.type_name()));
  if (!nd || nd->is_none()) {
    if (is_intlike(x)) return Value::integer(x.as_int());
    return Value::integer(float_to_int(std::nearbyint(x.as_double())));
  }
  const int64_t n = integer("round", *nd);
  if (is_intlike(x)) {
    if (n >= 0) return Value::integer(x.as_int());
    int64_t p = 1;
    for (int64_t k = 0; k < -n && p < INT64_MAX / 10; ++k) p *= 10;
    const int64_t v = x.as_int();
    int64_t q = v / p, r = v % p;
    if (r < 0) {
      r += p;
      --q;
    }
    if (2 * r > p || (2 * r == p && (q & 1))) ++q;
    return Value::integer(q * p);
  }
  const double d = x.as_double();
  if (!std::isfinite(d) || n > 323) return Value::floating(d);
  if (n < -308) return Value::floating(std::copysign(0.0, d));
  if (n >= 0) {
    char buf[512];
    std::snprintf(buf, sizeof buf, "%.*f", static_cast<int>(n), d);
    return Value::floating(std::strtod(buf, nullptr));
  }
  const double p = std::pow(10.0, static_cast<double>(-n));
  const double r = std::nearbyint(d / p) * p;
  return Value::floating(std::isfinite(r) ? r : std::copysign(0.0, d));
}

Value int_builtin(const List& args, const Kwargs& kwargs) {
  only_kwargs("int", kwargs, {"base"});
  arity("int", args, 0, 2);
  if (args.empty()) return Value::integer(0);
  const Value& x = args[0];
  const Value* base = args.size() > 1 ? &args[1] : kwarg(kwargs, "base");
  if (x.kind() == Kind::Str) {
    if (base) {
      const int64_t b = integer("int", *base);
      std::string s = strip(x.as_str(), {}, true, true);
      s.erase(std::remove(s.begin(), s.end(), '_'), s.end());
      if (b == 16 || b == 8 || b == 2 || b == 0) {
        std::string body = s, sign;
        if (!body.empty() && (body[0] == '-' || body[0] == '+')) {
          sign = body.substr(0, 1);
          body = body.substr(1);
        }
        if (body.size() > 2 && body[0] == '0' && std::strchr("xXoObB", body[1])) body = body.substr(2);
        s = sign + body;
      }
      char* end = nullptr;
      errno = 0;
      const long long v = std::strtoll(s.c_str(), &end, b == 0 ? 10 : static_cast<int>(b));
      if (s.empty() || *end || errno)
        raise("ValueError", fmt::format("invalid literal for int() with base {}: {}", b, repr(x)));
      return Value::integer(v);
    }
    if (auto clean = without_digit_underscores(x.as_str()))
      if (auto v = python_int(*clean)) return Value::integer(*v);
    raise("ValueError", fmt::format("invalid literal for int() with base 10: {}", repr(x)));
  }
  if (base) raise("TypeError", "int() can't convert non-string with explicit base");
  if (is_intlike(x)) return Value::integer(x.as_int());
  if (x.kind() == Kind::Float) return Value::integer(float_to_int(std::trunc(x.as_double())));
  raise("TypeError", fmt::format("int() argument must be a string, a bytes-like object or a real number, not '{}'",
                                 x.type_name()));
}

Value float_builtin(const List& args, const Kwargs& kwargs) {
  no_kwargs("float", kwargs);
  arity("float", args, 0, 1);
  if (args.empty()) return Value::floating(0.0);
  const Value& x = args[0];
  if (x.kind() == Kind::Str) {
    if (auto clean = without_digit_underscores(x.as_str()))
      if (auto d = python_float(*clean)) return Value::floating(*d);
    raise("ValueError", fmt::format("could not convert string to float: {}", repr(x)));
  }
  if (x.is_number()) return Value::floating(x.as_double());
  raise("TypeError", fmt::format("float() argument must be a string or a real number, not '{}'", x.type_name()));
}

Value dict_builtin(const List& args, const Kwargs& kwargs) {
  arity("dict", args, 0, 1);
  Dict d;
  if (!args.empty()) {
    if (args[0].kind() == Kind::Dict) {
      d.items = args[0].as_dict().items;
    } else {
      const List items = iterate(args[0]);
      for (size_t i = 0; i < items.size(); ++i) {
        const List pair = iterate(items[i]);
        if (pair.size() != 2)
          raise("ValueError", fmt::format("dictionary update sequence element #{} has length {}; 2 is required", i,
                                          pair.size()));
        d.set(pair[0], pair[1]);
      }
    }
  }
  for (const auto& [k, v] : kwargs) d.set(Value::string(k), v);
  return Value::dict(std::move(d));
}

Value range_builtin(const List& args, const Kwargs& kwargs) {
  no_kwargs("range", kwargs);
  arity("range", args, 1, 3);
  int64_t start = 0, stop, step = 1;
  if (args.size() == 1) {
    stop = integer("range", args[0]);
  } else {
    start = integer("range", args[0]);
    stop = integer("range", args[1]);
    if (args.size() == 3) step = integer("range", args[2]);
  }
  if (step == 0) raise("ValueError", "range() arg 3 must not be zero");
  List out;
  for (int64_t i = start; step > 0 ? i < stop : i > stop; i += step) {
    out.push_back(Value::integer(i));
    if (out.size() > 10000000) raise("MemoryError", "range too large");
  }
  return Value::list(std::move(out));
}

Value sum_builtin(const List& args, const Kwargs& kwargs) {
  only_kwargs("sum", kwargs, {"start"});
  arity("sum", args, 1, 2);
  const Value* start = args.size() > 1 ? &args[1] : kwarg(kwargs, "start");
  Value total = start ? *start : Value::integer(0);
  if (total.kind() == Kind::Str) raise("TypeError", "sum() can't sum strings [use ''.join(seq) instead]");
  for (const Value& v : iterate(args[0])) total = binary(ast::Op::Add, total, v);
  return total;
}

Value sorted_builtin(const List& args, const Kwargs& kwargs) {
  only_kwargs("sorted", kwargs, {"key", "reverse"});
  arity("sorted", args, 1, 1);
  List items = iterate(args[0]);
  const Value* key = kwarg(kwargs, "key");
  const bool reverse = kwarg(kwargs, "reverse") && truthy(*kwarg(kwargs, "reverse"));
  std::vector<std::pair<Value, size_t>> keyed;
  for (size_t i = 0; i < items.size(); ++i)
    keyed.emplace_back(key && !key->is_none() ? call(*key, {items[i]}) : items[i], i);
  if (reverse) std::reverse(keyed.begin(), keyed.end());
  std::stable_sort(keyed.begin(), keyed.end(), [reverse](const auto& a, const auto& b) {
    return compare(ast::Cmp::Lt, reverse ? b.first : a.first, reverse ? a.first : b.first);
  });
  if (reverse) std::reverse(keyed.begin(), keyed.end());
  List out;
  for (const auto& [k, i] : keyed) out.push_back(items[i]);
  if (reverse) std::reverse(out.begin(), out.end());
  return Value::list(std::move(out));
}

bool isinstance_of(const Value& v, const Value& type) {
  if (type.kind() == Kind::Tuple) {
    for (const Value& t : type.as_list())
      if (isinstance_of(v, t)) return true;
    return false;
  }
  if (type.kind() != Kind::Callable)
    raise("TypeError", "isinstance() arg 2 must be a type, a tuple of types, or a union");
  const std::string& t = type.as_callable().name;
  if (t == v.type_name()) return true;
  return t == "int" && v.kind() == Kind::Bool;
}

Value zip_builtin(const List& args, const Kwargs& kwargs) {
  no_kwargs("zip", kwargs);
  std::vector<List> lists;
  size_t n = args.empty() ? 0 : SIZE_MAX;
  for (const Value& a : args) {
    lists.push_back(iterate(a));
    n = std::min(n, lists.back().size());
  }
  List out;
  for (size_t i = 0; i < n; ++i) {
    List t;
    for (const List& l : lists) t.push_back(l[i]);
    out.push_back(Value::tuple(std::move(t)));
  }
  return Value::list(std::move(out));
}

Value map_builtin(const List& args, const Kwargs& kwargs) {
  no_kwargs("map", kwargs);
  if (args.size() < 2) raise("TypeError", "map() must have at least two arguments.");
  const Value zipped = zip_builtin(List(args.begin() + 1, args.end()), {});
  List out;
  for (const Value& t : zipped.as_list()) out.push_back(call(args[0], t.as_list()));
  return Value::list(std::move(out));
}

// ---- math -------------------------------------------------------------------------------------------------------

[[noreturn]] void domain() { raise("ValueError", "math domain error"); }

Fn unary_math(const char* name, double (*f)(double), bool inf_is_domain) {
  return [name, f, inf_is_domain](const List& args, const Kwargs& kwargs) {
    no_kwargs(name, kwargs);
    arity(name, args, 1, 1);
    const double x = number(name, args[0]);
    const double r = f(x);
    if (std::isnan(r) && !std::isnan(x)) domain();
    if (std::isinf(r) && std::isfinite(x)) {
      if (inf_is_domain) domain();
      raise("OverflowError", "math range error");
    }
    return Value::floating(r);
  };
}

double degrees(double x) { return x * (180.0 / M_PI); }
double radians(double x) { return x * (M_PI / 180.0); }
double fabs_(double x) { return std::fabs(x); }
double gamma_(double x) {
  if (x <= 0 && x == std::floor(x)) domain();
  return std::tgamma(x);
}
double lgamma_(double x) {
  if (x <= 0 && x == std::floor(x)) domain();
  return std::lgamma(x);
}
double log_(double x) {
  if (x <= 0) domain();
  return std::log(x);
}
double log2_(double x) {
  if (x <= 0) domain();
  return std::log2(x);
}
double log10_(double x) {
  if (x <= 0) domain();
  return std::log10(x);
}
double log1p_(double x) {
  if (x <= -1) domain();
  return std::log1p(x);
}

Fn rounding(const char* name, double (*f)(double)) {
  return [name, f](const List& args, const Kwargs& kwargs) {
    no_kwargs(name, kwargs);
    arity(name, args, 1, 1);
    if (is_intlike(args[0])) return Value::integer(args[0].as_int());
    return Value::integer(float_to_int(f(number(name, args[0]))));
  };
}

Fn binary_math(const char* name, double (*f)(double, double)) {
  return [name, f](const List& args, const Kwargs& kwargs) {
    no_kwargs(name, kwargs);
    arity(name, args, 2, 2);
    const double x = number(name, args[0]), y = number(name, args[1]);
    const double r = f(x, y);
    if (std::isnan(r) && !std::isnan(x) && !std::isnan(y)) domain();
    return Value::floating(r);
  };
}

double math_pow(double x, double y) {
  if (x == 0 && y < 0) domain();
  if (x < 0 && std::isfinite(x) && std::isfinite(y) && y != std::floor(y)) domain();
  const double r = std::pow(x, y);
  if (std::isinf(r) && std::isfinite(x) && std::isfinite(y)) raise("OverflowError", "math range error");
  return r;
}

double math_fmod(double x, double y) {
  if (y == 0 || std::isinf(x)) {
    if (std::isnan(x) || std::isnan(y)) return NAN;
    domain();
  }
  return std::fmod(x, y);
}

double math_remainder(double x, double y) {
  if ((y == 0 || std::isinf(x)) && !std::isnan(x) && !std::isnan(y)) domain();
  return std::remainder(x, y);
}

int64_t gcd2(int64_t a, int64_t b) { return std::gcd(a, b); }

void add_math(std::unordered_map<std::string, Value>& m) {
  auto add = [&](const char* name, Fn fn) { m[name] = Value::callable(name, std::move(fn)); };
  m["pi"] = Value::floating(M_PI);
  m["e"] = Value::floating(M_E);
  m["tau"] = Value::floating(2 * M_PI);
  m["inf"] = Value::floating(std::numeric_limits<double>::infinity());
  m["nan"] = Value::floating(std::numeric_limits<double>::quiet_NaN());
  struct U {
    const char* name;
    double (*f)(double);
    bool inf_is_domain;
  };
  static const U unary[] = {
      {"sin", static_cast<double (*)(double)>(std::sin), false},     {"cos", static_cast<double (*)(double)>(std::cos), false},
      {"tan", static_cast<double (*)(double)>(std::tan), false},     {"asin", static_cast<double (*)(double)>(std::asin), false},
      {"acos", static_cast<double (*)(double)>(std::acos), false},   {"atan", static_cast<double (*)(double)>(std::atan), false},
      {"sinh", static_cast<double (*)(double)>(std::sinh), false},   {"cosh", static_cast<double (*)(double)>(std::cosh), false},
      {"tanh", static_cast<double (*)(double)>(std::tanh), false},   {"asinh", static_cast<double (*)(double)>(std::asinh), false},
      {"acosh", static_cast<double (*)(double)>(std::acosh), false}, {"atanh", static_cast<double (*)(double)>(std::atanh), true},
      {"sqrt", static_cast<double (*)(double)>(std::sqrt), false},   {"cbrt", static_cast<double (*)(double)>(std::cbrt), false},
      {"exp", static_cast<double (*)(double)>(std::exp), false},     {"exp2", static_cast<double (*)(double)>(std::exp2), false},
      {"expm1", static_cast<double (*)(double)>(std::expm1), false}, {"log2", log2_, true},
      {"log10", log10_, true},                                       {"log1p", log1p_, true},
      {"fabs", fabs_, false},                                        {"degrees", degrees, false},
      {"radians", radians, false},                                   {"erf", static_cast<double (*)(double)>(std::erf), false},
      {"erfc", static_cast<double (*)(double)>(std::erfc), false},   {"gamma", gamma_, false},
      {"lgamma", lgamma_, false},
  };
  for (const U& u : unary) add(u.name, unary_math(u.name, u.f, u.inf_is_domain));
  add("floor", rounding("floor", std::floor));
  add("ceil", rounding("ceil", std::ceil));
  add("trunc", rounding("trunc", std::trunc));
  add("atan2", binary_math("atan2", static_cast<double (*)(double, double)>(std::atan2)));
  add("copysign", binary_math("copysign", static_cast<double (*)(double, double)>(std::copysign)));
  add("pow", binary_math("pow", math_pow));
  add("fmod", binary_math("fmod", math_fmod));
  add("remainder", binary_math("remainder", math_remainder));
  add("nextafter", binary_math("nextafter", static_cast<double (*)(double, double)>(std::nextafter)));
  add("log", [](const List& args, const Kwargs& kwargs) {
    no_kwargs("log", kwargs);
    arity("log", args, 1, 2);
    const double x = log_(number("log", args[0]));
    if (args.size() == 1) return Value::floating(x);
    const double b = log_(number("log", args[1]));
    if (b == 0) raise("ZeroDivisionError", "float division by zero");
    return Value::floating(x / b);
  });
  add("hypot", [](const List& args, const Kwargs& kwargs) {
    no_kwargs("hypot", kwargs);
    double r = 0;
    for (const Value& a : args) r = std::hypot(r, number("hypot", a));
    return Value::floating(r);
  });
  add("dist", [](const List& args, const Kwargs& kwargs) {
    no_kwargs("dist", kwargs);
    arity("dist", args, 2, 2);
    const List p = iterate(args[0]), q = iterate(args[1]);
    if (p.size() != q.size()) raise("ValueError", "both points must have the same number of dimensions");
    double r = 0;
    for (size_t i = 0; i < p.size(); ++i) r = std::hypot(r, number("dist", p[i]) - number("dist", q[i]));
    return Value::floating(r);
  });
  add("isfinite", [](const List& a, const Kwargs&) { arity("isfinite", a, 1, 1); return Value::boolean(std::isfinite(number("isfinite", a[0]))); });
  add("isinf", [](const List& a, const Kwargs&) { arity("isinf", a, 1, 1); return Value::boolean(std::isinf(number("isinf", a[0]))); });
  add("isnan", [](const List& a, const Kwargs&) { arity("isnan", a, 1, 1); return Value::boolean(std::isnan(number("isnan", a[0]))); });
  add("isclose", [](const List& args, const Kwargs& kwargs) {
    only_kwargs("isclose", kwargs, {"rel_tol", "abs_tol"});
    arity("isclose", args, 2, 2);
    const double a = number("isclose", args[0]), b = number("isclose", args[1]);
    const double rel = kwarg(kwargs, "rel_tol") ? number("isclose", *kwarg(kwargs, "rel_tol")) : 1e-9;
    const double abs_tol = kwarg(kwargs, "abs_tol") ? number("isclose", *kwarg(kwargs, "abs_tol")) : 0.0;
    if (rel < 0 || abs_tol < 0) raise("ValueError", "tolerances must be non-negative");
    if (a == b) return Value::boolean(true);
    if (std::isinf(a) || std::isinf(b)) return Value::boolean(false);
    const double diff = std::fabs(b - a);
    return Value::boolean(diff <= std::fabs(rel * b) || diff <= std::fabs(rel * a) || diff <= abs_tol);
  });
  add("frexp", [](const List& args, const Kwargs&) {
    arity("frexp", args, 1, 1);
    int e = 0;
    const double m = std::frexp(number("frexp", args[0]), &e);
    return Value::tuple({Value::floating(m), Value::integer(e)});
  });
  add("ldexp", [](const List& args, const Kwargs&) {
    arity("ldexp", args, 2, 2);
    const double x = number("ldexp", args[0]);
    const double r = std::ldexp(x, static_cast<int>(std::clamp<int64_t>(integer("ldexp", args[1]), -100000, 100000)));
    if (std::isinf(r) && std::isfinite(x)) raise("OverflowError", "math range error");
    return Value::floating(r);
  });
  add("modf", [](const List& args, const Kwargs&) {
    arity("modf", args, 1, 1);
    double ip = 0;
    const double fp = std::modf(number("modf", args[0]), &ip);
    return Value::tuple({Value::floating(fp), Value::floating(ip)});
  });
  add("fsum", [](const List& args, const Kwargs&) {
    arity("fsum", args, 1, 1);
    std::vector<double> partials;
    for (const Value& v : iterate(args[0])) {
      double x = number("fsum", v);
      size_t i = 0;
      for (double y : partials) {
        if (std::fabs(x) < std::fabs(y)) std::swap(x, y);
        const double hi = x + y;
        const double lo = y - (hi - x);
        if (lo != 0) partials[i++] = lo;
        x = hi;
      }
      partials.resize(i);
      partials.push_back(x);
    }
    double total = 0;
    for (double p : partials) total += p;
    return Value::floating(total);
  });
  add("prod", [](const List& args, const Kwargs& kwargs) {
    only_kwargs("prod", kwargs, {"start"});
    arity("prod", args, 1, 1);
    Value total = kwarg(kwargs, "start") ? *kwarg(kwargs, "start") : Value::integer(1);
    for (const Value& v : iterate(args[0])) total = binary(ast::Op::Mul, total, v);
    return total;
  });
  add("factorial", [](const List& args, const Kwargs&) {
    arity("factorial", args, 1, 1);
    const int64_t n = integer("factorial", args[0]);
    if (n < 0) raise("ValueError", "factorial() not defined for negative values");
    Value r = Value::integer(1);
    for (int64_t i = 2; i <= n; ++i) r = binary(ast::Op::Mul, r, Value::integer(i));
    return r;
  });
  add("gcd", [](const List& args, const Kwargs&) {
    int64_t r = 0;
    for (const Value& a : args) r = gcd2(r, integer("gcd", a));
    return Value::integer(r);
  });
  add("lcm", [](const List& args, const Kwargs&) {
    int64_t r = 1;
    for (const Value& a : args) {
      const int64_t x = integer("lcm", a);
      if (x == 0) return Value::integer(0);
      r = std::abs(r / gcd2(r, x) * x);
    }
    return Value::integer(r);
  });
  add("isqrt", [](const List& args, const Kwargs&) {
    arity("isqrt", args, 1, 1);
    const int64_t n = integer("isqrt", args[0]);
    if (n < 0) raise("ValueError", "isqrt() argument must be nonnegative");
    int64_t r = static_cast<int64_t>(std::sqrt(static_cast<double>(n)));
    while (r * r > n) --r;
    while ((r + 1) * (r + 1) <= n) ++r;
    return Value::integer(r);
  });
  auto comb_perm = [](bool comb) {
    return [comb](const List& args, const Kwargs&) {
      arity(comb ? "comb" : "perm", args, comb ? 2 : 1, 2);
      const int64_t n = integer("comb", args[0]);
      const int64_t k = args.size() > 1 ? integer("comb", args[1]) : n;
      if (n < 0 || k < 0) raise("ValueError", "n and k must be non-negative integers");
      if (k > n) return Value::integer(0);
      Value r = Value::integer(1);
      for (int64_t i = 0; i < k; ++i) {
        r = binary(ast::Op::Mul, r, Value::integer(n - i));
        if (comb) r = binary(ast::Op::FloorDiv, r, Value::integer(i + 1));
      }
      return r;
    };
  };
  add("comb", comb_perm(true));
  add("perm", comb_perm(false));
  add("ulp", [](const List& args, const Kwargs&) {
    arity("ulp", args, 1, 1);
    const double x = std::fabs(number("ulp", args[0]));
    if (std::isnan(x) || std::isinf(x)) return Value::floating(x);
    const double next = std::nextafter(x, INFINITY);
    if (std::isinf(next)) return Value::floating(x - std::nextafter(x, -INFINITY));
    return Value::floating(next - x);
  });
}

Value type_value(const std::string& name, Fn fn) { return Value::callable(name, std::move(fn)); }

struct Tables {
  std::unordered_map<std::string, Value> globals;
  Value math;
  Value python;
};

Tables make_tables() {
  Tables t;
  std::unordered_map<std::string, Value> math;
  add_math(math);
  std::unordered_map<std::string, Value> b;
  auto add = [&](const char* name, Fn fn) { b[name] = Value::callable(name, std::move(fn)); };
  add("len", [](const List& args, const Kwargs& kwargs) {
    no_kwargs("len", kwargs);
    arity("len", args, 1, 1);
    const Value& v = args[0];
    switch (v.kind()) {
      case Kind::Str: return Value::integer(static_cast<int64_t>(v.as_str().size()));
      case Kind::List:
      case Kind::Tuple: return Value::integer(static_cast<int64_t>(v.as_list().size()));
      case Kind::Dict: return Value::integer(static_cast<int64_t>(v.as_dict().items.size()));
      default: raise("TypeError", fmt::format("object of type '{}' has no len()", v.type_name()));
    }
  });
  add("min", [](const List& a, const Kwargs& k) { return min_max("min", false, a, k); });
  add("max", [](const List& a, const Kwargs& k) { return min_max("max", true, a, k); });
  add("abs", [](const List& args, const Kwargs& kwargs) {
    no_kwargs("abs", kwargs);
    arity("abs", args, 1, 1);
    const Value& v = args[0];
    if (is_intlike(v)) {
      if (v.as_int() == INT64_MIN) raise("OverflowError", "integer result does not fit in 64 bits");
      return Value::integer(std::abs(v.as_int()));
    }
    if (v.kind() == Kind::Float) return Value::floating(std::fabs(v.as_double()));
    raise("TypeError", fmt::format("bad operand type for abs(): '{}'", v.type_name()));
  });
  b["int"] = type_value("int", int_builtin);
  b["float"] = type_value("float", float_builtin);
  b["str"] = type_value("str", [](const List& args, const Kwargs& kwargs) {
    no_kwargs("str", kwargs);
    arity("str", args, 0, 1);
    return Value::string(args.empty() ? "" : str(args[0]));
  });
  b["bool"] = type_value("bool", [](const List& args, const Kwargs& kwargs) {
    no_kwargs("bool", kwargs);
    arity("bool", args, 0, 1);
    return Value::boolean(!args.empty() && truthy(args[0]));
  });
  b["list"] = type_value("list", [](const List& args, const Kwargs& kwargs) {
    no_kwargs("list", kwargs);
    arity("list", args, 0, 1);
    return Value::list(args.empty() ? List() : iterate(args[0]));
  });
  b["tuple"] = type_value("tuple", [](const List& args, const Kwargs& kwargs) {
    no_kwargs("tuple", kwargs);
    arity("tuple", args, 0, 1);
    return Value::tuple(args.empty() ? List() : iterate(args[0]));
  });
  b["dict"] = type_value("dict", dict_builtin);
  add("round", round_builtin);
  add("sorted", sorted_builtin);
  add("range", range_builtin);
  add("sum", sum_builtin);
  add("any", [](const List& args, const Kwargs&) {
    arity("any", args, 1, 1);
    for (const Value& v : iterate(args[0]))
      if (truthy(v)) return Value::boolean(true);
    return Value::boolean(false);
  });
  add("all", [](const List& args, const Kwargs&) {
    arity("all", args, 1, 1);
    for (const Value& v : iterate(args[0]))
      if (!truthy(v)) return Value::boolean(false);
    return Value::boolean(true);
  });
  add("zip", zip_builtin);
  add("map", map_builtin);
  add("filter", [](const List& args, const Kwargs&) {
    arity("filter", args, 2, 2);
    List out;
    for (const Value& v : iterate(args[1]))
      if (args[0].is_none() ? truthy(v) : truthy(call(args[0], {v}))) out.push_back(v);
    return Value::list(std::move(out));
  });
  add("enumerate", [](const List& args, const Kwargs& kwargs) {
    only_kwargs("enumerate", kwargs, {"start"});
    arity("enumerate", args, 1, 2);
    const Value* s = args.size() > 1 ? &args[1] : kwarg(kwargs, "start");
    int64_t i = s ? integer("enumerate", *s) : 0;
    List out;
    for (const Value& v : iterate(args[0])) out.push_back(Value::tuple({Value::integer(i++), v}));
    return Value::list(std::move(out));
  });
  add("reversed", [](const List& args, const Kwargs&) {
    arity("reversed", args, 1, 1);
    List items = iterate(args[0]);
    std::reverse(items.begin(), items.end());
    return Value::list(std::move(items));
  });
  add("isinstance", [](const List& args, const Kwargs&) {
    arity("isinstance", args, 2, 2);
    return Value::boolean(isinstance_of(args[0], args[1]));
  });
  add("repr", [](const List& args, const Kwargs&) {
    arity("repr", args, 1, 1);
    return Value::string(repr(args[0]));
  });
  add("divmod", [](const List& args, const Kwargs&) {
    arity("divmod", args, 2, 2);
    return Value::tuple({binary(ast::Op::FloorDiv, args[0], args[1]), binary(ast::Op::Mod, args[0], args[1])});
  });
  add("ord", [](const List& args, const Kwargs&) {
    arity("ord", args, 1, 1);
    const std::string& s = str_arg("ord", args[0]);
    if (s.size() != 1)
      raise("TypeError", fmt::format("ord() expected a character, but string of length {} found", s.size()));
    return Value::integer(static_cast<unsigned char>(s[0]));
  });
  add("chr", [](const List& args, const Kwargs&) {
    arity("chr", args, 1, 1);
    const int64_t c = integer("chr", args[0]);
    if (c < 0 || c > 127) raise("ValueError", "chr() arg outside the supported ASCII range");
    return Value::string(std::string(1, static_cast<char>(c)));
  });
  add("format", [](const List& args, const Kwargs&) {
    arity("format", args, 1, 2);
    return Value::string(format_value(args[0], args.size() > 1 ? str_arg("format", args[1]) : ""));
  });
  b["type"] = Value::callable("type", [](const List& args, const Kwargs&) {
    arity("type", args, 1, 1);
    const std::string name = args[0].type_name();
    const auto& g = builtins();
    auto it = g.find(name);
    if (it != g.end() && it->second.kind() == Kind::Callable && it->second.as_callable().name == name)
      return it->second;
    return Value::callable(name, [name](const List&, const Kwargs&) -> Value {
      raise("TypeError", fmt::format("cannot create '{}' instances", name));
    });
  });

  Dict python;
  python.attribute_access = true;
  for (const auto& [k, v] : b) python.set(Value::string(k), v);
  python.set(Value::string("True"), Value::boolean(true));
  python.set(Value::string("False"), Value::boolean(false));
  t.python = Value::dict(std::move(python));
  Dict m;
  m.attribute_access = true;
  std::vector<std::string> names;
  for (const auto& kv : math) names.push_back(kv.first);
  std::sort(names.begin(), names.end());
  for (const std::string& n : names) m.set(Value::string(n), math[n]);
  t.math = Value::dict(std::move(m));
  t.globals = std::move(b);
  for (auto& [k, v] : math) t.globals[k] = v;
  t.globals["math"] = t.math;
  t.globals["python"] = t.python;
  return t;
}

const Tables& tables() {
  static const Tables t = make_tables();
  return t;
}

}  // namespace

const std::unordered_map<std::string, Value>& builtins() { return tables().globals; }

bool is_module(const Value& v, const char** name) {
  if (v.kind() != Kind::Dict) return false;
  if (&v.as_dict() == &tables().math.as_dict()) {
    *name = "math";
    return true;
  }
  if (&v.as_dict() == &tables().python.as_dict()) {
    *name = "python";
    return true;
  }
  return false;
}

std::optional<Value> method(const Value& self, const std::string& name) {
  switch (self.kind()) {
    case Kind::Str: return str_method(self, name);
    case Kind::List:
    case Kind::Tuple: return sequence_method(self, name);
    case Kind::Dict: {
      const char* module = nullptr;
      if (is_module(self, &module)) return std::nullopt;
      return dict_method(self, name);
    }
    case Kind::Float:
      if (name == "is_integer")
        return bound(self, "is_integer", [](const Value& s, const List&, const Kwargs&) {
          const double d = s.as_double();
          return Value::boolean(std::isfinite(d) && d == std::floor(d));
        });
      return std::nullopt;
    default: return std::nullopt;
  }
}

std::string format_value(const Value& v, std::string_view spec_text) {
  if (spec_text.empty()) return str(v);
  const Spec spec = parse_spec(spec_text);
  switch (v.kind()) {
    case Kind::Str:
      if (spec.type && spec.type != 's')
        raise("ValueError", fmt::format("Unknown format code '{}' for object of type 'str'", spec.type));
      return pad("", spec.precision >= 0 ? v.as_str().substr(0, static_cast<size_t>(spec.precision)) : v.as_str(),
                 spec, '<');
    case Kind::Bool:
    case Kind::Int:
      if (spec.type == 0 && v.kind() == Kind::Bool) return pad("", str(v), spec, '<');
      if (spec.type == 0 || std::strchr("dnbxXoc", spec.type)) {
        if (spec.precision >= 0) raise("ValueError", "Precision not allowed in integer format specifier");
        return format_int(v.as_int(), spec);
      }
      if (std::strchr("eEfFgG%", spec.type)) return format_float(v.as_double(), spec);
      raise("ValueError", fmt::format("Unknown format code '{}' for object of type 'int'", spec.type));
    case Kind::Float:
      if (spec.type == 0 || std::strchr("eEfFgGn%", spec.type)) return format_float(v.as_double(), spec);
      raise("ValueError", fmt::format("Unknown format code '{}' for object of type 'float'", spec.type));
    default:
      raise("TypeError", fmt::format("unsupported format string passed to {}.__format__", v.type_name()));
  }
}

std::string percent_format(const std::string& f, const Value& args) {
  const List items = args.kind() == Kind::Tuple ? args.as_list() : List{args};
  const bool mapping = args.kind() == Kind::Dict;
  size_t next = 0;
  std::string out;
  for (size_t i = 0; i < f.size(); ++i) {
    if (f[i] != '%') {
      out += f[i];
      continue;
    }
    if (++i >= f.size()) raise("ValueError", "incomplete format");
    Value v;
    bool have = false;
    if (f[i] == '(') {
      const size_t close = f.find(')', i);
      if (close == std::string::npos) raise("ValueError", "incomplete format key");
      if (!mapping) raise("TypeError", "format requires a mapping");
      v = index(args, Value::string(f.substr(i + 1, close - i - 1)));
      have = true;
      i = close + 1;
    }
    Spec spec;
    bool left = false;
    for (; i < f.size() && std::strchr("-+ #0", f[i]); ++i) {
      if (f[i] == '-') left = true;
      if (f[i] == '+' || f[i] == ' ') spec.sign = spec.sign == '+' ? '+' : f[i];
      if (f[i] == '#') spec.alternate = true;
      if (f[i] == '0') spec.fill = '0';
    }
    while (i < f.size() && std::isdigit(static_cast<unsigned char>(f[i]))) spec.width = spec.width * 10 + (f[i++] - '0');
    if (i < f.size() && f[i] == '.') {
      spec.precision = 0;
      for (++i; i < f.size() && std::isdigit(static_cast<unsigned char>(f[i])); ++i)
        spec.precision = spec.precision * 10 + (f[i] - '0');
    }
    if (i >= f.size()) raise("ValueError", "incomplete format");
    const char conv = f[i];
    if (conv == '%') {
      out += '%';
      continue;
    }
    if (!have) {
      if (mapping || next >= items.size()) raise("TypeError", "not enough arguments for format string");
      v = items[next++];
    }
    if (left) {
      spec.align = '<';
      spec.fill = ' ';
    } else if (spec.fill == '0') {
      spec.align = '=';
    }
    if (conv == 's' || conv == 'r' || conv == 'a') {
      std::string s = conv == 's' ? str(v) : repr(v);
      if (spec.precision >= 0) s = s.substr(0, static_cast<size_t>(spec.precision));
      spec.fill = ' ';
      out += pad("", s, spec, '>');
    } else if (std::strchr("diu", conv)) {
      if (!v.is_number()) raise("TypeError", fmt::format("%{} format: a real number is required, not {}", conv, v.type_name()));
      spec.type = 'd';
      out += format_int(is_intlike(v) ? v.as_int() : float_to_int(std::trunc(v.as_double())), spec);
    } else if (std::strchr("xXoc", conv)) {
      if (!is_intlike(v)) raise("TypeError", fmt::format("%{} format: an integer is required, not {}", conv, v.type_name()));
      spec.type = conv;
      out += format_int(v.as_int(), spec);
    } else if (std::strchr("eEfFgG", conv)) {
      if (!v.is_number()) raise("TypeError", "must be real number, not " + v.type_name());
      spec.type = conv;
      if (spec.precision < 0) spec.precision = 6;
      out += format_float(v.as_double(), spec);
    } else {
      raise("ValueError", fmt::format("unsupported format character '{}' (0x{:x}) at index {}", conv,
                                      static_cast<int>(conv), i));
    }
  }
  if (!mapping && next < items.size() && args.kind() == Kind::Tuple)
    raise("TypeError", "not all arguments converted during string formatting");
  if (!mapping && args.kind() != Kind::Tuple && next == 0 && f.find('%') != std::string::npos && items.size() == 1) {
    bool any_conversion = false;
    for (size_t k = 0; k + 1 < f.size(); ++k)
      if (f[k] == '%') {
        if (f[k + 1] != '%') any_conversion = true;
        ++k;
      }
    if (!any_conversion) raise("TypeError", "not all arguments converted during string formatting");
  }
  return out;
}

}  // namespace lcm_control::xacro::py
