// The str methods of xacro's expressions and Python's formatting: str.format, format(v, spec) and '%'.
#include <algorithm>
#include <climits>
#include <cstring>
#include <vector>

#include "xacro/budget.hpp"
#include "xacro/python/python_args.hpp"
#include "xacro/python/utf8.hpp"

namespace lcm_control::xacro::py {

namespace {

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

// A width or precision's digits from s[i], saturating, checked against the string budget (a width is the size of
// the string it pads to).
size_t format_number(std::string_view s, size_t& i) {
  size_t n = 0;
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
    n = std::min<size_t>(n * 10 + static_cast<size_t>(s[i++] - '0'), size_t{1} << 62);
  check_string(n);
  return n;
}

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
  spec.width = format_number(s, i);
  if (i < s.size() && (s[i] == ',' || s[i] == '_')) spec.grouping = s[i++];
  if (i < s.size() && s[i] == '.') {
    ++i;
    if (i >= s.size() || !std::isdigit(static_cast<unsigned char>(s[i]))) raise("ValueError", "Format specifier missing precision");
    spec.precision = 0;
    spec.precision = static_cast<int>(std::min<size_t>(format_number(s, i), INT_MAX));
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

}  // namespace

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

namespace {

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

}  // namespace


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
        check_string(out.size() + s.size() + items[i].as_str().size());
        if (i) out += s;
        out += items[i].as_str();
      }
      return Value::string(std::move(out));
    });
  if (name == "upper" || name == "lower") {
    const bool up = name == "upper";
    return simple([up](const std::string& s, Args args) {
      arity(up ? "upper" : "lower", args, 0, 0);
      std::string out;
      out.reserve(s.size());
      for (size_t i = 0; i < s.size();) {
        const uint32_t cp = next_code_point(s, i);
        append_utf8(out, up ? upper_case(cp) : lower_case(cp));
      }
      return Value::string(std::move(out));
    });
  }
  if (name == "title" || name == "capitalize") {
    const bool title = name == "title";
    return simple([title](const std::string& s, Args args) {
      arity(title ? "title" : "capitalize", args, 0, 0);
      std::string out;
      out.reserve(s.size());
      bool start = true;
      for (size_t i = 0; i < s.size();) {
        const uint32_t cp = next_code_point(s, i);
        append_utf8(out, start ? upper_case(cp) : lower_case(cp));
        start = title ? !is_cased_letter(cp) : false;
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
            check_string(out.size());
            --limit;
          }
          if (k < s.size()) out += s[k];
        }
        return Value::string(std::move(out));
      }
      for (size_t j; limit != 0 && (j = s.find(from, i)) != std::string::npos; --limit) {
        out.append(s, i, j - i).append(to);
        check_string(out.size());
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
      // Positions are code points (Python's str): a non-ASCII string's are mapped to bytes and back.
      const std::vector<size_t> cps = is_ascii(s) ? std::vector<size_t>{} : code_point_starts(s);
      auto byte_at = [&](int64_t cp) { return cps.empty() ? size_t(cp) : cps[size_t(cp)]; };
      const int64_t size = static_cast<int64_t>(cps.empty() ? s.size() : cps.size() - 1);
      auto clamp = [&](int64_t i) { return std::clamp<int64_t>(i < 0 ? i + size : i, 0, size); };
      const size_t start = byte_at(args.size() > 1 ? clamp(integer(which.c_str(), args[1])) : 0);
      const size_t end = byte_at(args.size() > 2 ? clamp(integer(which.c_str(), args[2])) : size);
      const std::string part = end > start ? s.substr(start, end - start) : "";
      if (which == "count") return Value::integer(static_cast<int64_t>(count_occurrences(part, sub)));
      const size_t at = which[0] == 'r' ? part.rfind(sub) : part.find(sub);
      if (at == std::string::npos) {
        if (which == "index" || which == "rindex") raise("ValueError", "substring not found");
        return Value::integer(-1);
      }
      const size_t byte = at + start;
      if (cps.empty()) return Value::integer(static_cast<int64_t>(byte));
      return Value::integer(static_cast<int64_t>(std::lower_bound(cps.begin(), cps.end(), byte) - cps.begin()));
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
      const size_t length = code_point_count(s);
      if (static_cast<int64_t>(length) >= width) return Value::string(s);
      check_string(static_cast<size_t>(width));
      const size_t fill = static_cast<size_t>(width) - length;
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
    spec.width = format_number(f, i);
    if (i < f.size() && f[i] == '.') {
      ++i;
      spec.precision = static_cast<int>(std::min<size_t>(format_number(f, i), INT_MAX));
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
