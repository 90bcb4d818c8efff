// Python's operations on values, shared by the evaluator (python_expr.cpp) and the built-ins (python_builtins.cpp).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

#include "xacro/python/python_ast.hpp"
#include "xacro/python/value.hpp"

namespace lcm_control::xacro::py {

[[noreturn]] void raise(const char* python_type, const std::string& message);

Value binary(ast::Op op, const Value& a, const Value& b);
bool compare(ast::Cmp cmp, const Value& a, const Value& b);
bool contains(const Value& container, const Value& item);
List iterate(const Value& v);  // the items of list(v)
Value call(const Value& f, const List& args, const Kwargs& kwargs = {});
Value index(const Value& target, const Value& key);
Value attribute(const Value& target, const std::string& name);

// python_builtins.cpp
const std::unordered_map<std::string, Value>& builtins();
std::optional<Value> method(const Value& self, const std::string& name);  // a bound method, if self has one
std::string format_value(const Value& v, std::string_view spec);          // format(v, spec)
std::string percent_format(const std::string& format, const Value& args);  // format % args
bool is_module(const Value& v, const char** name);                          // math, python

}  // namespace lcm_control::xacro::py
