// The built-ins of xacro's expressions: Python's functions and types, the `math` and `python` namespaces, and
// the methods of list, tuple, dict and float.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "xacro/budget.hpp"
#include "xacro/python/python_args.hpp"
#include "xacro/python/python_literals.hpp"
#include "xacro/python/utf8.hpp"

namespace lcm_control::xacro::py {

namespace {

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
  const __int128 span = step > 0 ? __int128{stop} - start : __int128{start} - stop;  // no int64 overflow
  const __int128 stride = step > 0 ? __int128{step} : -__int128{step};
  const __int128 count = span <= 0 ? 0 : (span + stride - 1) / stride;
  check_list(count > (__int128{1} << 62) ? size_t{1} << 62 : static_cast<size_t>(count));
  List out;
  out.reserve(static_cast<size_t>(count));
  for (__int128 k = 0; k < count; ++k) out.push_back(Value::integer(static_cast<int64_t>(start + k * step)));
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
      case Kind::Str: return Value::integer(static_cast<int64_t>(code_point_count(v.as_str())));
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

}  // namespace lcm_control::xacro::py
