// Argument checks and conversions shared by the built-ins (python_builtins.cpp, python_strings.cpp,
// python_math.cpp).
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <unordered_map>

#include "xacro/python/python_eval.hpp"

namespace lcm_control::xacro::py {

using Fn = std::function<Value(const List&, const Kwargs&)>;
using Kind = Value::Kind;

inline bool is_intlike(const Value& v) { return v.kind() == Kind::Int || v.kind() == Kind::Bool; }

inline void arity(const char* name, const List& args, size_t min, size_t max) {
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

inline void no_kwargs(const char* name, const Kwargs& kwargs) {
  if (!kwargs.empty()) raise("TypeError", fmt::format("{}() takes no keyword arguments", name));
}

inline const Value* kwarg(const Kwargs& kwargs, const char* name) {
  for (const auto& [k, v] : kwargs)
    if (k == name) return &v;
  return nullptr;
}

inline void only_kwargs(const char* fn, const Kwargs& kwargs, std::initializer_list<const char*> allowed) {
  for (const auto& kv : kwargs)
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return kv.first == a; }))
      raise("TypeError", fmt::format("{}() got an unexpected keyword argument '{}'", fn, kv.first));
}

inline double number(const char* fn, const Value& v) {
  if (!v.is_number()) raise("TypeError", fmt::format("must be real number, not {}", v.type_name()));
  (void)fn;
  return v.as_double();
}

inline int64_t integer(const char* fn, const Value& v) {
  if (!is_intlike(v))
    raise("TypeError", fmt::format("'{}' object cannot be interpreted as an integer", v.type_name()));
  (void)fn;
  return v.as_int();
}

inline int64_t float_to_int(double d) {
  if (std::isinf(d)) raise("OverflowError", "cannot convert float infinity to integer");
  if (std::isnan(d)) raise("ValueError", "cannot convert float NaN to integer");
  if (d >= 9223372036854775808.0 || d < -9223372036854775808.0)
    raise("OverflowError", "integer result does not fit in 64 bits");
  return static_cast<int64_t>(d);
}

inline Value bound(const Value& self, const char* name, std::function<Value(const Value&, const List&, const Kwargs&)> fn) {
  return Value::callable(fmt::format("{}.{}", self.type_name(), name),
                         [self, fn = std::move(fn)](const List& args, const Kwargs& kwargs) {
                           return fn(self, args, kwargs);
                         });
}

inline const std::string& str_arg(const char* method, const Value& v) {
  if (v.kind() != Kind::Str)
    raise("TypeError", fmt::format("{}() argument must be str, not {}", method, v.type_name()));
  return v.as_str();
}

std::string strip(const std::string& s, const List& args, bool left, bool right);  // str.strip(args)
std::optional<Value> str_method(const Value& self, const std::string& name);
void add_math(std::unordered_map<std::string, Value>& globals);

}  // namespace lcm_control::xacro::py
