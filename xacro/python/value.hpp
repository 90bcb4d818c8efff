// The values of xacro's `${...}` expressions: Python's None, bool, int, float, str, list, dict and callables, with
// Python's own str()/repr() (so a float prints as the official xacro prints it: 0.1, 1e-05, 100000.0) and truth.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <variant>
#include <vector>

namespace lcm_control::xacro {

class Value;
using List = std::vector<Value>;
using Kwargs = std::vector<std::pair<std::string, Value>>;

// A Python dict: insertion-ordered. `attribute_access` marks xacro's dotified dicts (xacro.load_yaml, xacro.dotify),
// whose keys may also be read as `d.key`.
struct Dict {
  std::vector<std::pair<Value, Value>> items;  // change them only through set(): `index` follows them
  bool attribute_access = false;
  const Value* find(const Value& key) const;
  void set(Value key, Value value);  // replaces an equal key in place, else appends

 private:
  std::size_t position(const Value& key) const;  // items.size() when absent
  std::unordered_multimap<std::size_t, std::size_t> index;  // key hash -> position in items, from 8 items on
};

// A built-in function, a bound method ("a b".split) or one the processor supplies (xacro.load_yaml).
struct Callable {
  std::string name;  // for messages: "len", "str.split", "xacro.load_yaml"
  std::function<Value(const List& args, const Kwargs& kwargs)> call;
};

// Python's exceptions, by the Python name ("NameError", "TypeError", "ZeroDivisionError", "SyntaxError", ...), with
// Python's message ("name 'x' is not defined").
class EvalError : public std::runtime_error {
 public:
  EvalError(std::string python_type, const std::string& message)
      : std::runtime_error(python_type + ": " + message), type_(std::move(python_type)) {}
  const std::string& python_type() const { return type_; }

 private:
  std::string type_;
};

class Value {
 public:
  enum class Kind { None, Bool, Int, Float, Str, List, Tuple, Dict, Callable };

  Value() = default;  // None
  static Value none() { return Value(); }
  static Value boolean(bool b);
  static Value integer(int64_t i);
  static Value floating(double d);
  static Value string(std::string s);
  static Value list(List items);
  static Value tuple(List items);
  static Value dict(Dict d);
  static Value callable(std::string name, std::function<Value(const List&, const Kwargs&)> fn);

  Kind kind() const;
  bool is_none() const { return kind() == Kind::None; }
  bool is_number() const { return kind() == Kind::Bool || kind() == Kind::Int || kind() == Kind::Float; }

  // Accessors throw EvalError("TypeError", ...) on the wrong kind.
  bool as_bool() const;
  int64_t as_int() const;      // bool and int
  double as_double() const;    // bool, int and float
  const std::string& as_str() const;
  const List& as_list() const;  // list and tuple
  const Dict& as_dict() const;
  const Callable& as_callable() const;

  // Python's type name: "NoneType", "bool", "int", "float", "str", "list", "tuple", "dict", "builtin_function_or_method".
  std::string type_name() const;

 private:
  std::variant<std::monostate, bool, int64_t, double, std::string, std::shared_ptr<const List>,
               std::shared_ptr<const List>, std::shared_ptr<const Dict>, std::shared_ptr<const Callable>>
      v_;
};

// Python's str(v) and repr(v): str("a") is a, repr("a") is 'a'; floats as Python's repr (shortest round trip,
// exponent below 1e-4 and from 1e16: 1e-05, 1e+16, 100000.0, -0.0, inf, nan).
std::string str(const Value& v);
std::string repr(const Value& v);
std::string float_repr(double d);
// Python's truth: None, False, 0, 0.0, "", [], {} are false.
bool truthy(const Value& v);
// Python's ==, with 1 == 1.0 == True.
bool equal(const Value& a, const Value& b);

}  // namespace lcm_control::xacro
