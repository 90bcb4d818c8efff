// Python values for xacro's expressions: construction, accessors, str()/repr() as CPython prints them, truth, ==.
#include "xacro/python/value.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdlib>

#include "xacro/budget.hpp"
#include "rt/escape.hpp"

namespace lcm_control::xacro {

namespace {

constexpr size_t kNone = 0, kBool = 1, kInt = 2, kFloat = 3, kStr = 4, kList = 5, kTuple = 6, kDict = 7,
                 kCallable = 8;

EvalError wrong_kind(const char* expected, const Value& v) {
  return EvalError("TypeError", fmt::format("expected {}, got '{}'", expected, v.type_name()));
}

std::string str_repr(const std::string& s) {
  const bool has_single = s.find('\'') != std::string::npos;
  const bool has_double = s.find('"') != std::string::npos;
  const char quote = has_single && !has_double ? '"' : '\'';
  const char backslashed[] = {quote, '\\', '\0'};
  return quote + escape_controls(s, false, backslashed) + quote;
}

bool numeric_equal(const Value& a, const Value& b) {
  if (a.kind() == Value::Kind::Float || b.kind() == Value::Kind::Float) return a.as_double() == b.as_double();
  return a.as_int() == b.as_int();
}

}  // namespace

namespace {

// Python's hash contract: values that compare equal hash equal (1, 1.0 and True alike). Lists and dicts, which
// Python refuses as keys, all hash alike.
std::size_t hash_of(const Value& v) {
  switch (v.kind()) {
    case Value::Kind::Bool:
    case Value::Kind::Int: return std::hash<int64_t>{}(v.as_int());
    case Value::Kind::Float: {
      const double d = v.as_double();
      if (d == std::floor(d) && std::abs(d) < 9.2e18) return std::hash<int64_t>{}(static_cast<int64_t>(d));
      return std::hash<double>{}(d);
    }
    case Value::Kind::Str: return std::hash<std::string>{}(v.as_str());
    case Value::Kind::Tuple: {
      std::size_t h = 0x345678;
      for (const Value& item : v.as_list()) h = h * 1000003 ^ hash_of(item);
      return h;
    }
    default: return static_cast<std::size_t>(v.kind());
  }
}

constexpr std::size_t kIndexFrom = 8;  // below, a linear search is as quick

}  // namespace

std::size_t Dict::position(const Value& key) const {
  if (index.empty()) {
    for (std::size_t i = 0; i < items.size(); ++i)
      if (equal(items[i].first, key)) return i;
    return items.size();
  }
  auto [first, last] = index.equal_range(hash_of(key));
  for (auto it = first; it != last; ++it)
    if (equal(items[it->second].first, key)) return it->second;
  return items.size();
}

const Value* Dict::find(const Value& key) const {
  const std::size_t i = position(key);
  return i < items.size() ? &items[i].second : nullptr;
}

void Dict::set(Value key, Value value) {
  const std::size_t i = position(key);
  if (i < items.size()) {
    items[i].second = std::move(value);
    return;
  }
  items.emplace_back(std::move(key), std::move(value));
  if (items.size() == kIndexFrom) {
    for (std::size_t i = 0; i < items.size(); ++i) index.emplace(hash_of(items[i].first), i);
  } else if (items.size() > kIndexFrom) {
    index.emplace(hash_of(items.back().first), items.size() - 1);
  }
}

Value Value::boolean(bool b) {
  Value v;
  v.v_.emplace<kBool>(b);
  return v;
}

Value Value::integer(int64_t i) {
  Value v;
  v.v_.emplace<kInt>(i);
  return v;
}

Value Value::floating(double d) {
  Value v;
  v.v_.emplace<kFloat>(d);
  return v;
}

Value Value::string(std::string s) {
  check_string(s.size());
  Value v;
  v.v_.emplace<kStr>(std::move(s));
  return v;
}

Value Value::list(List items) {
  check_list(items.size());
  Value v;
  v.v_.emplace<kList>(std::make_shared<const List>(std::move(items)));
  return v;
}

Value Value::tuple(List items) {
  check_list(items.size());
  Value v;
  v.v_.emplace<kTuple>(std::make_shared<const List>(std::move(items)));
  return v;
}

Value Value::dict(Dict d) {
  check_list(d.items.size());
  Value v;
  v.v_.emplace<kDict>(std::make_shared<const Dict>(std::move(d)));
  return v;
}

Value Value::callable(std::string name, std::function<Value(const List&, const Kwargs&)> fn) {
  Value v;
  v.v_.emplace<kCallable>(std::make_shared<const Callable>(Callable{std::move(name), std::move(fn)}));
  return v;
}

Value::Kind Value::kind() const { return static_cast<Kind>(v_.index()); }

bool Value::as_bool() const {
  if (v_.index() == kBool) return std::get<kBool>(v_);
  if (v_.index() == kInt) return std::get<kInt>(v_) != 0;
  throw wrong_kind("bool", *this);
}

int64_t Value::as_int() const {
  if (v_.index() == kInt) return std::get<kInt>(v_);
  if (v_.index() == kBool) return std::get<kBool>(v_) ? 1 : 0;
  throw wrong_kind("int", *this);
}

double Value::as_double() const {
  switch (v_.index()) {
    case kFloat: return std::get<kFloat>(v_);
    case kInt: return static_cast<double>(std::get<kInt>(v_));
    case kBool: return std::get<kBool>(v_) ? 1.0 : 0.0;
    default: throw wrong_kind("float", *this);
  }
}

const std::string& Value::as_str() const {
  if (v_.index() == kStr) return std::get<kStr>(v_);
  throw wrong_kind("str", *this);
}

const List& Value::as_list() const {
  if (v_.index() == kList) return *std::get<kList>(v_);
  if (v_.index() == kTuple) return *std::get<kTuple>(v_);
  throw wrong_kind("list", *this);
}

const Dict& Value::as_dict() const {
  if (v_.index() == kDict) return *std::get<kDict>(v_);
  throw wrong_kind("dict", *this);
}

const Callable& Value::as_callable() const {
  if (v_.index() == kCallable) return *std::get<kCallable>(v_);
  throw wrong_kind("callable", *this);
}

std::string Value::type_name() const {
  switch (kind()) {
    case Kind::None: return "NoneType";
    case Kind::Bool: return "bool";
    case Kind::Int: return "int";
    case Kind::Float: return "float";
    case Kind::Str: return "str";
    case Kind::List: return "list";
    case Kind::Tuple: return "tuple";
    case Kind::Dict: return "dict";
    case Kind::Callable: return "builtin_function_or_method";
  }
  return "object";
}

std::string float_repr(double d) {
  if (std::isnan(d)) return "nan";
  if (std::isinf(d)) return d < 0 ? "-inf" : "inf";
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, d, std::chars_format::scientific);
  const std::string_view sci(buf, static_cast<size_t>(res.ptr - buf));
  const size_t e = sci.find('e');
  std::string digits;
  bool negative = false;
  for (char c : sci.substr(0, e)) {
    if (c == '-')
      negative = true;
    else if (c != '.')
      digits += c;
  }
  const int exponent = std::atoi(std::string(sci.substr(e + 1)).c_str());
  std::string out = negative ? "-" : "";
  const int n = static_cast<int>(digits.size());
  if (exponent < -4 || exponent >= 16) {
    out += digits[0];
    if (n > 1) out += "." + digits.substr(1);
    out += fmt::format("e{}{:02d}", exponent < 0 ? '-' : '+', std::abs(exponent));
    return out;
  }
  const int point = exponent + 1;
  if (point <= 0) {
    out += "0." + std::string(static_cast<size_t>(-point), '0') + digits;
  } else if (point >= n) {
    out += digits + std::string(static_cast<size_t>(point - n), '0') + ".0";
  } else {
    out += digits.substr(0, static_cast<size_t>(point)) + "." + digits.substr(static_cast<size_t>(point));
  }
  return out;
}

std::string repr(const Value& v) {
  switch (v.kind()) {
    case Value::Kind::None: return "None";
    case Value::Kind::Bool: return v.as_int() ? "True" : "False";
    case Value::Kind::Int: return std::to_string(v.as_int());
    case Value::Kind::Float: return float_repr(v.as_double());
    case Value::Kind::Str: return str_repr(v.as_str());
    case Value::Kind::List:
    case Value::Kind::Tuple: {
      const bool tuple = v.kind() == Value::Kind::Tuple;
      const List& items = v.as_list();
      std::string out = tuple ? "(" : "[";
      for (size_t i = 0; i < items.size(); ++i) {
        if (i) out += ", ";
        out += repr(items[i]);
        check_string(out.size());
      }
      if (tuple && items.size() == 1) out += ",";
      out += tuple ? ")" : "]";
      return out;
    }
    case Value::Kind::Dict: {
      std::string out = "{";
      bool first = true;
      for (const auto& [k, val] : v.as_dict().items) {
        if (!first) out += ", ";
        first = false;
        out += repr(k) + ": " + repr(val);
        check_string(out.size());
      }
      return out + "}";
    }
    case Value::Kind::Callable: {
      const std::string& name = v.as_callable().name;
      static const char* const types[] = {"int", "float", "str", "bool", "list", "tuple", "dict", "type", "NoneType"};
      for (const char* t : types)
        if (name == t) return "<class '" + name + "'>";
      return "<built-in function " + name + ">";
    }
  }
  return "";
}

std::string str(const Value& v) { return v.kind() == Value::Kind::Str ? v.as_str() : repr(v); }

bool truthy(const Value& v) {
  switch (v.kind()) {
    case Value::Kind::None: return false;
    case Value::Kind::Bool:
    case Value::Kind::Int: return v.as_int() != 0;
    case Value::Kind::Float: return v.as_double() != 0.0;
    case Value::Kind::Str: return !v.as_str().empty();
    case Value::Kind::List:
    case Value::Kind::Tuple: return !v.as_list().empty();
    case Value::Kind::Dict: return !v.as_dict().items.empty();
    case Value::Kind::Callable: return true;
  }
  return false;
}

bool equal(const Value& a, const Value& b) {
  if (a.is_number() && b.is_number()) return numeric_equal(a, b);
  if (a.kind() != b.kind()) return false;
  switch (a.kind()) {
    case Value::Kind::None: return true;
    case Value::Kind::Str: return a.as_str() == b.as_str();
    case Value::Kind::List:
    case Value::Kind::Tuple: {
      const List& x = a.as_list();
      const List& y = b.as_list();
      if (x.size() != y.size()) return false;
      for (size_t i = 0; i < x.size(); ++i)
        if (!equal(x[i], y[i])) return false;
      return true;
    }
    case Value::Kind::Dict: {
      const Dict& x = a.as_dict();
      const Dict& y = b.as_dict();
      if (x.items.size() != y.items.size()) return false;
      for (const auto& [k, v] : x.items) {
        const Value* other = y.find(k);
        if (!other || !equal(v, *other)) return false;
      }
      return true;
    }
    case Value::Kind::Callable: return &a.as_callable() == &b.as_callable();
    default: return false;
  }
}

}  // namespace lcm_control::xacro
