// xacro's `${...}` expressions: the evaluator of the parsed AST and Python's operators (see python_expr.hpp).
#include "xacro/python/python_expr.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <vector>

#include "xacro/budget.hpp"
#include "xacro/python/python_ast.hpp"
#include "xacro/python/python_eval.hpp"
#include "xacro/python/utf8.hpp"

namespace lcm_control::xacro {

namespace py {

using ast::Cmp;
using ast::Op;

void raise(const char* python_type, const std::string& message) { throw EvalError(python_type, message); }

namespace {

const char* op_symbol(Op op) {
  switch (op) {
    case Op::Add: return "+";
    case Op::Sub: return "-";
    case Op::Mul: return "*";
    case Op::Div: return "/";
    case Op::FloorDiv: return "//";
    case Op::Mod: return "%";
    case Op::Pow: return "** or pow()";
    case Op::BitAnd: return "&";
    case Op::BitOr: return "|";
    case Op::BitXor: return "^";
    case Op::Shl: return "<<";
    case Op::Shr: return ">>";
    default: return "?";
  }
}

[[noreturn]] void unsupported(Op op, const Value& a, const Value& b) {
  raise("TypeError", fmt::format("unsupported operand type(s) for {}: '{}' and '{}'", op_symbol(op), a.type_name(),
                                 b.type_name()));
}

[[noreturn]] void overflow() { raise("OverflowError", "integer result does not fit in 64 bits"); }

bool is_intlike(const Value& v) { return v.kind() == Value::Kind::Int || v.kind() == Value::Kind::Bool; }
bool is_sequence(const Value& v) { return v.kind() == Value::Kind::List || v.kind() == Value::Kind::Tuple; }

int64_t floor_div(int64_t a, int64_t b) {
  if (b == 0) raise("ZeroDivisionError", "integer division or modulo by zero");
  if (a == INT64_MIN && b == -1) overflow();
  int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

int64_t floor_mod(int64_t a, int64_t b) {
  if (b == 0) raise("ZeroDivisionError", "integer modulo by zero");
  if (b == -1) return 0;
  int64_t m = a % b;
  if (m != 0 && ((m < 0) != (b < 0))) m += b;
  return m;
}

double float_mod(double x, double y) {
  if (y == 0) raise("ZeroDivisionError", "float modulo");
  double mod = std::fmod(x, y);
  if (mod != 0) {
    if ((y < 0) != (mod < 0)) mod += y;
  } else {
    mod = std::copysign(0.0, y);
  }
  return mod;
}

double float_floor_div(double x, double y) {
  if (y == 0) raise("ZeroDivisionError", "float floor division by zero");
  double mod = std::fmod(x, y);
  double div = (x - mod) / y;
  if (mod != 0) {
    if ((y < 0) != (mod < 0)) div -= 1.0;
  }
  if (div != 0) {
    double floordiv = std::floor(div);
    if (div - floordiv > 0.5) floordiv += 1.0;
    return floordiv;
  }
  return std::copysign(0.0, x / y);
}

Value int_pow(int64_t base, int64_t exp) {
  if (exp < 0) {
    if (base == 0) raise("ZeroDivisionError", "0.0 cannot be raised to a negative power");
    return Value::floating(std::pow(static_cast<double>(base), static_cast<double>(exp)));
  }
  int64_t result = 1;
  while (exp > 0) {
    if (exp & 1)
      if (__builtin_mul_overflow(result, base, &result)) overflow();
    exp >>= 1;
    if (exp > 0 && __builtin_mul_overflow(base, base, &base)) overflow();
  }
  return Value::integer(result);
}

double float_pow(double x, double y) {
  if (x == 0 && y < 0) raise("ZeroDivisionError", "0.0 cannot be raised to a negative power");
  if (x < 0 && std::isfinite(x) && std::isfinite(y) && y != std::floor(y))
    raise("ValueError", "a negative number raised to a fractional power is complex (not supported)");
  const double r = std::pow(x, y);
  if (std::isinf(r) && std::isfinite(x) && std::isfinite(y)) raise("OverflowError", "(34, 'Numerical result out of range')");
  return r;
}

// The bytes of the strings a list holds by value (nested lists are shared, not copied).
size_t string_bytes_in(const List& items) {
  size_t bytes = 0;
  for (const Value& v : items)
    if (v.kind() == Value::Kind::Str) bytes += v.as_str().size();
  return bytes;
}

// n copies of something of `size`, checked against the budget before anything is allocated.
size_t repeated(size_t size, int64_t n) {
  size_t total = 0;
  if (__builtin_mul_overflow(size, static_cast<size_t>(n), &total)) total = std::numeric_limits<size_t>::max();
  return total;
}

Value repeat(const Value& seq, const Value& count) {
  const int64_t n = std::max<int64_t>(0, count.as_int());
  if (seq.kind() == Value::Kind::Str) {
    check_string(repeated(seq.as_str().size(), n));
    std::string out;
    out.reserve(seq.as_str().size() * static_cast<size_t>(n));
    for (int64_t i = 0; i < n; ++i) out += seq.as_str();
    return Value::string(std::move(out));
  }
  check_list(repeated(seq.as_list().size(), n));
  check_string(repeated(string_bytes_in(seq.as_list()), n));
  List out;
  for (int64_t i = 0; i < n; ++i) out.insert(out.end(), seq.as_list().begin(), seq.as_list().end());
  return seq.kind() == Value::Kind::Tuple ? Value::tuple(std::move(out)) : Value::list(std::move(out));
}

Value numeric(Op op, const Value& a, const Value& b) {
  if (is_intlike(a) && is_intlike(b)) {
    const int64_t x = a.as_int(), y = b.as_int();
    int64_t r = 0;
    switch (op) {
      case Op::Add:
        if (__builtin_add_overflow(x, y, &r)) overflow();
        return Value::integer(r);
      case Op::Sub:
        if (__builtin_sub_overflow(x, y, &r)) overflow();
        return Value::integer(r);
      case Op::Mul:
        if (__builtin_mul_overflow(x, y, &r)) overflow();
        return Value::integer(r);
      case Op::Div:
        if (y == 0) raise("ZeroDivisionError", "division by zero");
        return Value::floating(static_cast<double>(x) / static_cast<double>(y));
      case Op::FloorDiv: return Value::integer(floor_div(x, y));
      case Op::Mod: return Value::integer(floor_mod(x, y));
      case Op::Pow: return int_pow(x, y);
      case Op::BitAnd:
        return a.kind() == Value::Kind::Bool && b.kind() == Value::Kind::Bool ? Value::boolean(x & y)
                                                                               : Value::integer(x & y);
      case Op::BitOr:
        return a.kind() == Value::Kind::Bool && b.kind() == Value::Kind::Bool ? Value::boolean(x | y)
                                                                               : Value::integer(x | y);
      case Op::BitXor:
        return a.kind() == Value::Kind::Bool && b.kind() == Value::Kind::Bool ? Value::boolean(x ^ y)
                                                                               : Value::integer(x ^ y);
      case Op::Shl:
        if (y < 0) raise("ValueError", "negative shift count");
        if (y >= 63 || (x != 0 && (x > (INT64_MAX >> y) || x < (INT64_MIN >> y)))) overflow();
        return Value::integer(x << y);
      case Op::Shr:
        if (y < 0) raise("ValueError", "negative shift count");
        return Value::integer(y >= 63 ? (x < 0 ? -1 : 0) : x >> y);
      default: break;
    }
  }
  const double x = a.as_double(), y = b.as_double();
  switch (op) {
    case Op::Add: return Value::floating(x + y);
    case Op::Sub: return Value::floating(x - y);
    case Op::Mul: return Value::floating(x * y);
    case Op::Div:
      if (y == 0) raise("ZeroDivisionError", "float division by zero");
      return Value::floating(x / y);
    case Op::FloorDiv: return Value::floating(float_floor_div(x, y));
    case Op::Mod: return Value::floating(float_mod(x, y));
    case Op::Pow: return Value::floating(float_pow(x, y));
    default: unsupported(op, a, b);
  }
}

template <class T>
bool ordered(Cmp cmp, const T& x, const T& y) {
  switch (cmp) {
    case Cmp::Lt: return x < y;
    case Cmp::Le: return x <= y;
    case Cmp::Gt: return x > y;
    case Cmp::Ge: return x >= y;
    default: return false;
  }
}

const char* cmp_symbol(Cmp cmp) {
  switch (cmp) {
    case Cmp::Lt: return "<";
    case Cmp::Le: return "<=";
    case Cmp::Gt: return ">";
    case Cmp::Ge: return ">=";
    default: return "?";
  }
}

bool identical(const Value& a, const Value& b) {
  if (a.kind() != b.kind()) return false;
  switch (a.kind()) {
    case Value::Kind::None: return true;
    case Value::Kind::List:
    case Value::Kind::Tuple: return &a.as_list() == &b.as_list();
    case Value::Kind::Dict: return &a.as_dict() == &b.as_dict();
    default: return equal(a, b);
  }
}

int64_t normalize_index(int64_t i, size_t size, const char* what) {
  const int64_t n = static_cast<int64_t>(size);
  if (i < 0) i += n;
  if (i < 0 || i >= n) raise("IndexError", fmt::format("{} index out of range", what));
  return i;
}

}  // namespace

Value binary(Op op, const Value& a, const Value& b) {
  if (a.is_number() && b.is_number()) return numeric(op, a, b);
  const auto ka = a.kind(), kb = b.kind();
  if (op == Op::Add) {
    if (ka == Value::Kind::Str && kb == Value::Kind::Str) {
      check_string(a.as_str().size() + b.as_str().size());
      return Value::string(a.as_str() + b.as_str());
    }
    if (is_sequence(a) && ka == kb) {
      check_list(a.as_list().size() + b.as_list().size());
      check_string(string_bytes_in(a.as_list()) + string_bytes_in(b.as_list()));
      List out = a.as_list();
      out.insert(out.end(), b.as_list().begin(), b.as_list().end());
      return ka == Value::Kind::Tuple ? Value::tuple(std::move(out)) : Value::list(std::move(out));
    }
    if (ka == Value::Kind::Str || is_sequence(a))
      raise("TypeError", fmt::format("can only concatenate {} (not \"{}\") to {}", a.type_name(), b.type_name(),
                                     a.type_name()));
  }
  if (op == Op::Mul) {
    if ((ka == Value::Kind::Str || is_sequence(a)) && is_intlike(b)) return repeat(a, b);
    if ((kb == Value::Kind::Str || is_sequence(b)) && is_intlike(a)) return repeat(b, a);
    if (ka == Value::Kind::Str || is_sequence(a) || kb == Value::Kind::Str || is_sequence(b)) {
      const Value& other = (ka == Value::Kind::Str || is_sequence(a)) ? b : a;
      raise("TypeError", fmt::format("can't multiply sequence by non-int of type '{}'", other.type_name()));
    }
  }
  if (op == Op::Mod && ka == Value::Kind::Str) return Value::string(percent_format(a.as_str(), b));
  unsupported(op, a, b);
}

bool compare(Cmp cmp, const Value& a, const Value& b) {
  switch (cmp) {
    case Cmp::Eq: return equal(a, b);
    case Cmp::Ne: return !equal(a, b);
    case Cmp::In: return contains(b, a);
    case Cmp::NotIn: return !contains(b, a);
    case Cmp::Is: return identical(a, b);
    case Cmp::IsNot: return !identical(a, b);
    default: break;
  }
  if (a.is_number() && b.is_number()) {
    if (is_intlike(a) && is_intlike(b)) return ordered(cmp, a.as_int(), b.as_int());
    return ordered(cmp, a.as_double(), b.as_double());
  }
  if (a.kind() == Value::Kind::Str && b.kind() == Value::Kind::Str) return ordered(cmp, a.as_str(), b.as_str());
  if (is_sequence(a) && a.kind() == b.kind()) {
    const List& x = a.as_list();
    const List& y = b.as_list();
    for (size_t i = 0; i < x.size() && i < y.size(); ++i)
      if (!equal(x[i], y[i])) return compare(cmp, x[i], y[i]);
    return ordered(cmp, x.size(), y.size());
  }
  raise("TypeError", fmt::format("'{}' not supported between instances of '{}' and '{}'", cmp_symbol(cmp),
                                 a.type_name(), b.type_name()));
}

bool contains(const Value& container, const Value& item) {
  switch (container.kind()) {
    case Value::Kind::Str:
      if (item.kind() != Value::Kind::Str)
        raise("TypeError", fmt::format("'in <string>' requires string as left operand, not {}", item.type_name()));
      return container.as_str().find(item.as_str()) != std::string::npos;
    case Value::Kind::List:
    case Value::Kind::Tuple:
      for (const Value& v : container.as_list())
        if (equal(v, item)) return true;
      return false;
    case Value::Kind::Dict: return container.as_dict().find(item) != nullptr;
    default:
      raise("TypeError", fmt::format("argument of type '{}' is not iterable", container.type_name()));
  }
}

List iterate(const Value& v) {
  switch (v.kind()) {
    case Value::Kind::List:
    case Value::Kind::Tuple: return v.as_list();
    case Value::Kind::Str: {
      List out;
      const std::string& s = v.as_str();
      check_list(code_point_count(s));
      for (size_t i = 0; i < s.size();) {
        size_t len = 1;
        const unsigned char c = static_cast<unsigned char>(s[i]);
        if (c >= 0xF0) len = 4;
        else if (c >= 0xE0) len = 3;
        else if (c >= 0xC0) len = 2;
        out.push_back(Value::string(s.substr(i, len)));
        i += len;
      }
      return out;
    }
    case Value::Kind::Dict: {
      List out;
      for (const auto& kv : v.as_dict().items) out.push_back(kv.first);
      return out;
    }
    default: raise("TypeError", fmt::format("'{}' object is not iterable", v.type_name()));
  }
}

Value call(const Value& f, const List& args, const Kwargs& kwargs) {
  if (f.kind() != Value::Kind::Callable) raise("TypeError", fmt::format("'{}' object is not callable", f.type_name()));
  return f.as_callable().call(args, kwargs);
}

Value index(const Value& target, const Value& key) {
  switch (target.kind()) {
    case Value::Kind::List:
    case Value::Kind::Tuple: {
      const char* what = target.kind() == Value::Kind::List ? "list" : "tuple";
      if (!is_intlike(key))
        raise("TypeError", fmt::format("{} indices must be integers or slices, not {}", what, key.type_name()));
      const List& items = target.as_list();
      return items[static_cast<size_t>(normalize_index(key.as_int(), items.size(), what))];
    }
    case Value::Kind::Str: {
      if (!is_intlike(key))
        raise("TypeError", fmt::format("string indices must be integers, not '{}'", key.type_name()));
      const std::string& s = target.as_str();
      if (is_ascii(s))
        return Value::string(std::string(1, s[static_cast<size_t>(normalize_index(key.as_int(), s.size(), "string"))]));
      const std::vector<size_t> at = code_point_starts(s);  // by code point, as Python's str
      const size_t k = static_cast<size_t>(normalize_index(key.as_int(), at.size() - 1, "string"));
      return Value::string(s.substr(at[k], at[k + 1] - at[k]));
    }
    case Value::Kind::Dict: {
      const Dict& d = target.as_dict();
      if (const Value* v = d.find(key)) return *v;
      if (d.attribute_access && key.kind() == Value::Kind::Str)
        raise("AttributeError", fmt::format("The yaml dictionary has no key '{}'", key.as_str()));
      raise("KeyError", repr(key));
    }
    default: raise("TypeError", fmt::format("'{}' object is not subscriptable", target.type_name()));
  }
}

Value attribute(const Value& target, const std::string& name) {
  if (auto m = method(target, name)) return *m;
  if (target.kind() == Value::Kind::Dict && target.as_dict().attribute_access) {
    if (const Value* v = target.as_dict().find(Value::string(name))) return *v;
    const char* module = nullptr;
    if (is_module(target, &module))
      raise("AttributeError", fmt::format("module '{}' has no attribute '{}'", module, name));
    raise("AttributeError", fmt::format("The yaml dictionary has no key '{}'", name));
  }
  raise("AttributeError", fmt::format("'{}' object has no attribute '{}'", target.type_name(), name));
}

}  // namespace py

namespace {

using ast::Node;
using ast::Op;
using Locals = std::vector<std::pair<std::string, Value>>;

class NoNames : public Names {
 public:
  std::optional<Value> lookup(const std::string&) const override { return std::nullopt; }
};

thread_local const Names* current_names = nullptr;

// Evaluation nests as deep as the expressions (the parser bounds each) times the lambdas calling lambdas: bounded
// here too, as Python's recursion limit does, far below what a thread's stack takes.
constexpr int kMaxEvalDepth = 2000;
thread_local int eval_depth = 0;
class EvalDepth {
 public:
  EvalDepth() {
    if (++eval_depth > kMaxEvalDepth || stack_nearly_full()) {
      const int levels = eval_depth--;
      py::raise("RecursionError",
                fmt::format("maximum recursion depth exceeded ({} levels of evaluation{}): a lambda that calls "
                            "itself without end?",
                            levels > kMaxEvalDepth ? kMaxEvalDepth : levels,
                            levels > kMaxEvalDepth ? "" : ", the thread's stack nearly full"));
    }
  }
  ~EvalDepth() { --eval_depth; }
  EvalDepth(const EvalDepth&) = delete;
  EvalDepth& operator=(const EvalDepth&) = delete;
};

class Evaluator {
 public:
  Evaluator(const Names& names, Locals locals) : names_(names), locals_(std::move(locals)) {}

  Value eval(const Node& n) {
    const EvalDepth depth;
    count_operation();
    switch (n.op) {
      case Op::Const: return n.value;
      case Op::Name: return name(n);
      case Op::Attr: return py::attribute(eval(*n.kids[0]), n.name);
      case Op::Index: return py::index(eval(*n.kids[0]), eval(*n.kids[1]));
      case Op::Slice: return slice(n);
      case Op::Call: return call(n);
      case Op::ListLit: return Value::list(eval_all(n));
      case Op::TupleLit: return Value::tuple(eval_all(n));
      case Op::DictLit: {
        Dict d;
        for (size_t i = 0; i + 1 < n.kids.size(); i += 2) d.set(eval(*n.kids[i]), eval(*n.kids[i + 1]));
        return Value::dict(std::move(d));
      }
      case Op::Neg:
      case Op::Pos:
      case Op::Invert: return unary(n);
      case Op::Not: return Value::boolean(!truthy(eval(*n.kids[0])));
      case Op::Compare: {
        Value left = eval(*n.kids[0]);
        for (size_t i = 0; i < n.cmps.size(); ++i) {
          Value right = eval(*n.kids[i + 1]);
          if (!py::compare(n.cmps[i], left, right)) return Value::boolean(false);
          left = std::move(right);
        }
        return Value::boolean(true);
      }
      case Op::And: {
        Value left = eval(*n.kids[0]);
        return truthy(left) ? eval(*n.kids[1]) : left;
      }
      case Op::Or: {
        Value left = eval(*n.kids[0]);
        return truthy(left) ? left : eval(*n.kids[1]);
      }
      case Op::IfElse: return truthy(eval(*n.kids[1])) ? eval(*n.kids[0]) : eval(*n.kids[2]);
      case Op::Comprehension: return comprehension(n);
      case Op::Lambda: return lambda(n);
      case Op::FString: {
        std::string out;
        for (size_t i = 0; i < n.kids.size(); ++i) {
          const std::string& spec = n.names[i];
          Value v = eval(*n.kids[i]);
          if (spec.empty()) {
            out += str(v);
            continue;
          }
          if (spec[0] == 'r' || spec[0] == 'a') v = Value::string(repr(v));
          if (spec[0] == 's') v = Value::string(str(v));
          out += py::format_value(v, std::string_view(spec).substr(spec.find(':') + 1));
        }
        return Value::string(std::move(out));
      }
      default: return py::binary(n.op, eval(*n.kids[0]), eval(*n.kids[1]));
    }
  }

 private:
  Value name(const Node& n) {
    for (auto it = locals_.rbegin(); it != locals_.rend(); ++it)
      if (it->first == n.name) return it->second;
    if (auto v = names_.lookup(n.name)) return *v;
    const auto& b = py::builtins();
    auto it = b.find(n.name);
    if (it != b.end()) return it->second;
    py::raise("NameError", fmt::format("name '{}' is not defined", n.name));
  }

  List eval_all(const Node& n) {
    List out;
    out.reserve(n.kids.size());
    for (const auto& k : n.kids) out.push_back(eval(*k));
    return out;
  }

  Value unary(const Node& n) {
    const Value v = eval(*n.kids[0]);
    const char* sym = n.op == Op::Neg ? "-" : n.op == Op::Pos ? "+" : "~";
    if (v.kind() == Value::Kind::Int || v.kind() == Value::Kind::Bool) {
      const int64_t i = v.as_int();
      if (n.op == Op::Pos) return Value::integer(i);
      if (n.op == Op::Invert) return Value::integer(~i);
      if (i == INT64_MIN) py::raise("OverflowError", "integer result does not fit in 64 bits");
      return Value::integer(-i);
    }
    if (v.kind() == Value::Kind::Float && n.op != Op::Invert)
      return Value::floating(n.op == Op::Neg ? -v.as_double() : v.as_double());
    py::raise("TypeError", fmt::format("bad operand type for unary {}: '{}'", sym, v.type_name()));
  }

  Value slice(const Node& n) {
    const Value target = eval(*n.kids[0]);
    auto bound = [&](size_t i) -> std::optional<int64_t> {
      if (!n.kids[i]) return std::nullopt;
      const Value v = eval(*n.kids[i]);
      if (v.is_none()) return std::nullopt;
      if (v.kind() != Value::Kind::Int && v.kind() != Value::Kind::Bool)
        py::raise("TypeError", "slice indices must be integers or None or have an __index__ method");
      return v.as_int();
    };
    const auto lower = bound(1), upper = bound(2), step_opt = bound(3);
    const int64_t step = step_opt.value_or(1);
    if (step == 0) py::raise("ValueError", "slice step cannot be zero");
    int64_t size;
    std::vector<size_t> at;  // a non-ASCII string's code points
    if (target.kind() == Value::Kind::Str) {
      if (!is_ascii(target.as_str())) at = code_point_starts(target.as_str());
      size = static_cast<int64_t>(at.empty() ? target.as_str().size() : at.size() - 1);
    }
    else if (target.kind() == Value::Kind::List || target.kind() == Value::Kind::Tuple)
      size = static_cast<int64_t>(target.as_list().size());
    else
      py::raise("TypeError", fmt::format("'{}' object is not subscriptable", target.type_name()));
    auto adjust = [&](std::optional<int64_t> v, int64_t dflt) {
      if (!v) return dflt;
      int64_t i = *v;
      if (i < 0) {
        i += size;
        if (i < 0) i = step < 0 ? -1 : 0;
      } else if (i >= size) {
        i = step < 0 ? size - 1 : size;
      }
      return i;
    };
    const int64_t start = adjust(lower, step < 0 ? size - 1 : 0);
    const int64_t stop = adjust(upper, step < 0 ? -1 : size);
    std::vector<size_t> picks;
    for (int64_t i = start; step > 0 ? i < stop : i > stop; i += step) picks.push_back(static_cast<size_t>(i));
    if (target.kind() == Value::Kind::Str) {
      std::string out;
      const std::string& s = target.as_str();
      for (size_t i : picks) {
        if (at.empty())
          out += s[i];
        else
          out.append(s, at[i], at[i + 1] - at[i]);
      }
      return Value::string(std::move(out));
    }
    List out;
    for (size_t i : picks) out.push_back(target.as_list()[i]);
    return target.kind() == Value::Kind::Tuple ? Value::tuple(std::move(out)) : Value::list(std::move(out));
  }

  Value call(const Node& n) {
    const Value f = eval(*n.kids[0]);
    const size_t positional = n.kids.size() - n.names.size();
    List args;
    args.reserve(positional - 1);
    for (size_t i = 1; i < positional; ++i) args.push_back(eval(*n.kids[i]));
    Kwargs kwargs;
    for (size_t i = 0; i < n.names.size(); ++i) {
      for (const auto& kw : kwargs)
        if (kw.first == n.names[i])
          py::raise("SyntaxError", fmt::format("keyword argument repeated: {}", n.names[i]));
      kwargs.emplace_back(n.names[i], eval(*n.kids[positional + i]));
    }
    return py::call(f, args, kwargs);
  }

  void bind(const ast::ForClause& f, const Value& item) {
    if (!f.tuple_target) {
      locals_.emplace_back(f.targets[0], item);
      return;
    }
    const List parts = py::iterate(item);
    if (parts.size() != f.targets.size())
      py::raise("ValueError", parts.size() < f.targets.size()
                                  ? fmt::format("not enough values to unpack (expected {}, got {})",
                                                f.targets.size(), parts.size())
                                  : fmt::format("too many values to unpack (expected {})", f.targets.size()));
    for (size_t i = 0; i < parts.size(); ++i) locals_.emplace_back(f.targets[i], parts[i]);
  }

  void generate(const Node& n, size_t level, List& out, Dict& dict_out, size_t& bytes) {
    if (level == n.fors.size()) {
      if (n.name == "dict")
        dict_out.set(eval(*n.kids[0]), eval(*n.kids[1]));
      else
        out.push_back(eval(*n.kids[0]));
      check_list(out.size() + dict_out.items.size());
      if (!out.empty() && out.back().kind() == Value::Kind::Str) check_string(bytes += out.back().as_str().size());
      return;
    }
    const ast::ForClause& f = n.fors[level];
    for (const Value& item : py::iterate(eval(*f.iter))) {
      const size_t mark = locals_.size();
      bind(f, item);
      bool keep = true;
      for (const auto& c : f.conditions)
        if (!(keep = truthy(eval(*c)))) break;
      if (keep) generate(n, level + 1, out, dict_out, bytes);
      locals_.resize(mark);
    }
  }

  Value comprehension(const Node& n) {
    List out;
    Dict d;
    size_t bytes = 0;  // of the strings `out` holds
    generate(n, 0, out, d, bytes);
    if (n.name == "dict") return Value::dict(std::move(d));
    return Value::list(std::move(out));
  }

  Value lambda(const Node& n) {
    auto body = n.kids[0];
    auto params = n.names;
    auto captured = std::make_shared<const Locals>(locals_);
    return Value::callable("<lambda>", [body, params, captured](const List& args, const Kwargs& kwargs) {
      Locals locals = *captured;
      if (args.size() + kwargs.size() != params.size())
        py::raise("TypeError", fmt::format("<lambda>() takes {} positional arguments but {} were given",
                                           params.size(), args.size() + kwargs.size()));
      for (size_t i = 0; i < args.size(); ++i) locals.emplace_back(params[i], args[i]);
      for (const auto& [k, v] : kwargs) {
        if (std::find(params.begin() + static_cast<std::ptrdiff_t>(args.size()), params.end(), k) == params.end())
          py::raise("TypeError", fmt::format("<lambda>() got an unexpected keyword argument '{}'", k));
        locals.emplace_back(k, v);
      }
      static const NoNames no_names;
      return Evaluator(current_names ? *current_names : no_names, std::move(locals)).eval(*body);
    });
  }

  const Names& names_;
  Locals locals_;
};

ast::NodePtr parsed(std::string_view expression) {
  thread_local std::unordered_map<std::string, ast::NodePtr> cache;
  std::string key(expression);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  ast::NodePtr n = ast::parse(expression);
  if (cache.size() >= 16384) cache.clear();
  cache.emplace(std::move(key), n);
  return n;
}

}  // namespace

Value evaluate(std::string_view expression, const Names& names) {
  const ast::NodePtr tree = parsed(expression);
  const Names* outer = current_names;
  current_names = &names;
  try {
    Value v = Evaluator(names, {}).eval(*tree);
    current_names = outer;
    return v;
  } catch (...) {
    current_names = outer;
    throw;
  }
}

}  // namespace lcm_control::xacro
