// xacro's `${...}` expressions: evaluation of the parsed Python subset (see python_expr.hpp).
#include "description/xacro/python_expr.hpp"

namespace lcm_control::xacro {

Value evaluate(std::string_view expression, const Names& names) {
  if (auto v = names.lookup(std::string(expression))) return *v;
  throw EvalError("SyntaxError", "expressions are not implemented yet: " + std::string(expression));
}

}  // namespace lcm_control::xacro
