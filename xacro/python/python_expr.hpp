// The Python subset of xacro's `${...}`: literals (int, float, str, True/False/None, lists, tuples, dicts), names,
// attribute access, indexing and slicing, calls with keyword arguments, + - * / // % ** and unary - + not,
// comparisons (chained), and/or (short-circuit), in / not in, is / is not, `a if c else b`; built-ins len, min, max,
// abs, int, float, str, bool, round, list, dict, sorted, range, sum, any, all, zip, map, isinstance, type and
// all of `math`, bare (pi, sin, radians) and as `math.`; string methods split, join, upper, lower, replace,
// startswith, endswith, format, strip, lstrip, rstrip, find, count; dict get/keys/values/items.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "xacro/python/value.hpp"

namespace lcm_control::xacro {

// The names an expression sees besides the built-ins: the processor's properties (evaluated lazily on lookup) and the
// `xacro` object. A name found here shadows a built-in of the same name, as a property shadows `pi` in xacro.
class Names {
 public:
  virtual ~Names() = default;
  virtual std::optional<Value> lookup(const std::string& name) const = 0;
};

// Evaluates one expression (the text between `${` and `}`, already free of `$(...)`). Throws EvalError:
// SyntaxError for text that does not parse, NameError for an unknown name, TypeError, ValueError, KeyError,
// IndexError, ZeroDivisionError as Python would.
Value evaluate(std::string_view expression, const Names& names);

}  // namespace lcm_control::xacro
