// The parsed form of a `${...}` expression (private to python_parse.cpp and python_expr.cpp).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "xacro/python/value.hpp"

namespace lcm_control::xacro::ast {

enum class Op {
  Const, Name, Attr, Index, Slice, Call, ListLit, TupleLit, DictLit, Neg, Pos, Not, Invert,
  Add, Sub, Mul, Div, FloorDiv, Mod, Pow, BitAnd, BitOr, BitXor, Shl, Shr,
  Compare, And, Or, IfElse, Comprehension, Lambda, FString
};

enum class Cmp { Lt, Le, Gt, Ge, Eq, Ne, In, NotIn, Is, IsNot };

struct Node;
using NodePtr = std::shared_ptr<const Node>;

// A `for targets in iter if cond...` clause of a comprehension.
struct ForClause {
  std::vector<std::string> targets;
  bool tuple_target = false;
  NodePtr iter;
  std::vector<NodePtr> conditions;
};

struct Node {
  Op op = Op::Const;
  int column = 1;
  Value value;                     // Const; FString: nothing
  std::string name;                // Name, Attr; Comprehension: "list", "gen", "dict"
  std::vector<NodePtr> kids;       // operands; Call: callee then positional args; Slice: target, lower, upper, step
  std::vector<std::string> names;  // Call: keyword names (kids' tail); Lambda: parameters; FString: format specs
  std::vector<Cmp> cmps;           // Compare: one between each pair of kids
  std::vector<ForClause> fors;     // Comprehension
};

// Parses the whole text as one expression; throws EvalError("SyntaxError", ...).
NodePtr parse(std::string_view text);

}  // namespace lcm_control::xacro::ast
