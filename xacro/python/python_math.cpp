// `math` for xacro's expressions: its constants and functions with Python's results and errors.
#include <limits>
#include <numeric>

#include "xacro/python/python_args.hpp"

namespace lcm_control::xacro::py {

namespace {

// ---- math -------------------------------------------------------------------------------------------------------

[[noreturn]] void domain() { raise("ValueError", "math domain error"); }

Fn unary_math(const char* name, double (*f)(double), bool inf_is_domain) {
  return [name, f, inf_is_domain](const List& args, const Kwargs& kwargs) {
    no_kwargs(name, kwargs);
    arity(name, args, 1, 1);
    const double x = number(name, args[0]);
    const double r = f(x);
    if (std::isnan(r) && !std::isnan(x)) domain();
    if (std::isinf(r) && std::isfinite(x)) {
      if (inf_is_domain) domain();
      raise("OverflowError", "math range error");
    }
    return Value::floating(r);
  };
}

double degrees(double x) { return x * (180.0 / M_PI); }
double radians(double x) { return x * (M_PI / 180.0); }
double fabs_(double x) { return std::fabs(x); }
double gamma_(double x) {
  if (x <= 0 && x == std::floor(x)) domain();
  return std::tgamma(x);
}
double lgamma_(double x) {
  if (x <= 0 && x == std::floor(x)) domain();
  return std::lgamma(x);
}
double log_(double x) {
  if (x <= 0) domain();
  return std::log(x);
}
double log2_(double x) {
  if (x <= 0) domain();
  return std::log2(x);
}
double log10_(double x) {
  if (x <= 0) domain();
  return std::log10(x);
}
double log1p_(double x) {
  if (x <= -1) domain();
  return std::log1p(x);
}

Fn rounding(const char* name, double (*f)(double)) {
  return [name, f](const List& args, const Kwargs& kwargs) {
    no_kwargs(name, kwargs);
    arity(name, args, 1, 1);
    if (is_intlike(args[0])) return Value::integer(args[0].as_int());
    return Value::integer(float_to_int(f(number(name, args[0]))));
  };
}

Fn binary_math(const char* name, double (*f)(double, double)) {
  return [name, f](const List& args, const Kwargs& kwargs) {
    no_kwargs(name, kwargs);
    arity(name, args, 2, 2);
    const double x = number(name, args[0]), y = number(name, args[1]);
    const double r = f(x, y);
    if (std::isnan(r) && !std::isnan(x) && !std::isnan(y)) domain();
    return Value::floating(r);
  };
}

double math_pow(double x, double y) {
  if (x == 0 && y < 0) domain();
  if (x < 0 && std::isfinite(x) && std::isfinite(y) && y != std::floor(y)) domain();
  const double r = std::pow(x, y);
  if (std::isinf(r) && std::isfinite(x) && std::isfinite(y)) raise("OverflowError", "math range error");
  return r;
}

double math_fmod(double x, double y) {
  if (y == 0 || std::isinf(x)) {
    if (std::isnan(x) || std::isnan(y)) return NAN;
    domain();
  }
  return std::fmod(x, y);
}

double math_remainder(double x, double y) {
  if ((y == 0 || std::isinf(x)) && !std::isnan(x) && !std::isnan(y)) domain();
  return std::remainder(x, y);
}

int64_t gcd2(int64_t a, int64_t b) { return std::gcd(a, b); }

}  // namespace

void add_math(std::unordered_map<std::string, Value>& m) {
  auto add = [&](const char* name, Fn fn) { m[name] = Value::callable(name, std::move(fn)); };
  m["pi"] = Value::floating(M_PI);
  m["e"] = Value::floating(M_E);
  m["tau"] = Value::floating(2 * M_PI);
  m["inf"] = Value::floating(std::numeric_limits<double>::infinity());
  m["nan"] = Value::floating(std::numeric_limits<double>::quiet_NaN());
  struct U {
    const char* name;
    double (*f)(double);
    bool inf_is_domain;
  };
  static const U unary[] = {
      {"sin", static_cast<double (*)(double)>(std::sin), false},     {"cos", static_cast<double (*)(double)>(std::cos), false},
      {"tan", static_cast<double (*)(double)>(std::tan), false},     {"asin", static_cast<double (*)(double)>(std::asin), false},
      {"acos", static_cast<double (*)(double)>(std::acos), false},   {"atan", static_cast<double (*)(double)>(std::atan), false},
      {"sinh", static_cast<double (*)(double)>(std::sinh), false},   {"cosh", static_cast<double (*)(double)>(std::cosh), false},
      {"tanh", static_cast<double (*)(double)>(std::tanh), false},   {"asinh", static_cast<double (*)(double)>(std::asinh), false},
      {"acosh", static_cast<double (*)(double)>(std::acosh), false}, {"atanh", static_cast<double (*)(double)>(std::atanh), true},
      {"sqrt", static_cast<double (*)(double)>(std::sqrt), false},   {"cbrt", static_cast<double (*)(double)>(std::cbrt), false},
      {"exp", static_cast<double (*)(double)>(std::exp), false},     {"exp2", static_cast<double (*)(double)>(std::exp2), false},
      {"expm1", static_cast<double (*)(double)>(std::expm1), false}, {"log2", log2_, true},
      {"log10", log10_, true},                                       {"log1p", log1p_, true},
      {"fabs", fabs_, false},                                        {"degrees", degrees, false},
      {"radians", radians, false},                                   {"erf", static_cast<double (*)(double)>(std::erf), false},
      {"erfc", static_cast<double (*)(double)>(std::erfc), false},   {"gamma", gamma_, false},
      {"lgamma", lgamma_, false},
  };
  for (const U& u : unary) add(u.name, unary_math(u.name, u.f, u.inf_is_domain));
  add("floor", rounding("floor", std::floor));
  add("ceil", rounding("ceil", std::ceil));
  add("trunc", rounding("trunc", std::trunc));
  add("atan2", binary_math("atan2", static_cast<double (*)(double, double)>(std::atan2)));
  add("copysign", binary_math("copysign", static_cast<double (*)(double, double)>(std::copysign)));
  add("pow", binary_math("pow", math_pow));
  add("fmod", binary_math("fmod", math_fmod));
  add("remainder", binary_math("remainder", math_remainder));
  add("nextafter", binary_math("nextafter", static_cast<double (*)(double, double)>(std::nextafter)));
  add("log", [](const List& args, const Kwargs& kwargs) {
    no_kwargs("log", kwargs);
    arity("log", args, 1, 2);
    const double x = log_(number("log", args[0]));
    if (args.size() == 1) return Value::floating(x);
    const double b = log_(number("log", args[1]));
    if (b == 0) raise("ZeroDivisionError", "float division by zero");
    return Value::floating(x / b);
  });
  add("hypot", [](const List& args, const Kwargs& kwargs) {
    no_kwargs("hypot", kwargs);
    double r = 0;
    for (const Value& a : args) r = std::hypot(r, number("hypot", a));
    return Value::floating(r);
  });
  add("dist", [](const List& args, const Kwargs& kwargs) {
    no_kwargs("dist", kwargs);
    arity("dist", args, 2, 2);
    const List p = iterate(args[0]), q = iterate(args[1]);
    if (p.size() != q.size()) raise("ValueError", "both points must have the same number of dimensions");
    double r = 0;
    for (size_t i = 0; i < p.size(); ++i) r = std::hypot(r, number("dist", p[i]) - number("dist", q[i]));
    return Value::floating(r);
  });
  add("isfinite", [](const List& a, const Kwargs&) { arity("isfinite", a, 1, 1); return Value::boolean(std::isfinite(number("isfinite", a[0]))); });
  add("isinf", [](const List& a, const Kwargs&) { arity("isinf", a, 1, 1); return Value::boolean(std::isinf(number("isinf", a[0]))); });
  add("isnan", [](const List& a, const Kwargs&) { arity("isnan", a, 1, 1); return Value::boolean(std::isnan(number("isnan", a[0]))); });
  add("isclose", [](const List& args, const Kwargs& kwargs) {
    only_kwargs("isclose", kwargs, {"rel_tol", "abs_tol"});
    arity("isclose", args, 2, 2);
    const double a = number("isclose", args[0]), b = number("isclose", args[1]);
    const double rel = kwarg(kwargs, "rel_tol") ? number("isclose", *kwarg(kwargs, "rel_tol")) : 1e-9;
    const double abs_tol = kwarg(kwargs, "abs_tol") ? number("isclose", *kwarg(kwargs, "abs_tol")) : 0.0;
    if (rel < 0 || abs_tol < 0) raise("ValueError", "tolerances must be non-negative");
    if (a == b) return Value::boolean(true);
    if (std::isinf(a) || std::isinf(b)) return Value::boolean(false);
    const double diff = std::fabs(b - a);
    return Value::boolean(diff <= std::fabs(rel * b) || diff <= std::fabs(rel * a) || diff <= abs_tol);
  });
  add("frexp", [](const List& args, const Kwargs&) {
    arity("frexp", args, 1, 1);
    int e = 0;
    const double m = std::frexp(number("frexp", args[0]), &e);
    return Value::tuple({Value::floating(m), Value::integer(e)});
  });
  add("ldexp", [](const List& args, const Kwargs&) {
    arity("ldexp", args, 2, 2);
    const double x = number("ldexp", args[0]);
    const double r = std::ldexp(x, static_cast<int>(std::clamp<int64_t>(integer("ldexp", args[1]), -100000, 100000)));
    if (std::isinf(r) && std::isfinite(x)) raise("OverflowError", "math range error");
    return Value::floating(r);
  });
  add("modf", [](const List& args, const Kwargs&) {
    arity("modf", args, 1, 1);
    double ip = 0;
    const double fp = std::modf(number("modf", args[0]), &ip);
    return Value::tuple({Value::floating(fp), Value::floating(ip)});
  });
  add("fsum", [](const List& args, const Kwargs&) {
    arity("fsum", args, 1, 1);
    std::vector<double> partials;
    for (const Value& v : iterate(args[0])) {
      double x = number("fsum", v);
      size_t i = 0;
      for (double y : partials) {
        if (std::fabs(x) < std::fabs(y)) std::swap(x, y);
        const double hi = x + y;
        const double lo = y - (hi - x);
        if (lo != 0) partials[i++] = lo;
        x = hi;
      }
      partials.resize(i);
      partials.push_back(x);
    }
    double total = 0;
    for (double p : partials) total += p;
    return Value::floating(total);
  });
  add("prod", [](const List& args, const Kwargs& kwargs) {
    only_kwargs("prod", kwargs, {"start"});
    arity("prod", args, 1, 1);
    Value total = kwarg(kwargs, "start") ? *kwarg(kwargs, "start") : Value::integer(1);
    for (const Value& v : iterate(args[0])) total = binary(ast::Op::Mul, total, v);
    return total;
  });
  add("factorial", [](const List& args, const Kwargs&) {
    arity("factorial", args, 1, 1);
    const int64_t n = integer("factorial", args[0]);
    if (n < 0) raise("ValueError", "factorial() not defined for negative values");
    Value r = Value::integer(1);
    for (int64_t i = 2; i <= n; ++i) r = binary(ast::Op::Mul, r, Value::integer(i));
    return r;
  });
  add("gcd", [](const List& args, const Kwargs&) {
    int64_t r = 0;
    for (const Value& a : args) r = gcd2(r, integer("gcd", a));
    return Value::integer(r);
  });
  add("lcm", [](const List& args, const Kwargs&) {
    int64_t r = 1;
    for (const Value& a : args) {
      const int64_t x = integer("lcm", a);
      if (x == 0) return Value::integer(0);
      r = std::abs(r / gcd2(r, x) * x);
    }
    return Value::integer(r);
  });
  add("isqrt", [](const List& args, const Kwargs&) {
    arity("isqrt", args, 1, 1);
    const int64_t n = integer("isqrt", args[0]);
    if (n < 0) raise("ValueError", "isqrt() argument must be nonnegative");
    int64_t r = static_cast<int64_t>(std::sqrt(static_cast<double>(n)));
    while (r * r > n) --r;
    while ((r + 1) * (r + 1) <= n) ++r;
    return Value::integer(r);
  });
  auto comb_perm = [](bool comb) {
    return [comb](const List& args, const Kwargs&) {
      arity(comb ? "comb" : "perm", args, comb ? 2 : 1, 2);
      const int64_t n = integer("comb", args[0]);
      const int64_t k = args.size() > 1 ? integer("comb", args[1]) : n;
      if (n < 0 || k < 0) raise("ValueError", "n and k must be non-negative integers");
      if (k > n) return Value::integer(0);
      Value r = Value::integer(1);
      for (int64_t i = 0; i < k; ++i) {
        r = binary(ast::Op::Mul, r, Value::integer(n - i));
        if (comb) r = binary(ast::Op::FloorDiv, r, Value::integer(i + 1));
      }
      return r;
    };
  };
  add("comb", comb_perm(true));
  add("perm", comb_perm(false));
  add("ulp", [](const List& args, const Kwargs&) {
    arity("ulp", args, 1, 1);
    const double x = std::fabs(number("ulp", args[0]));
    if (std::isnan(x) || std::isinf(x)) return Value::floating(x);
    const double next = std::nextafter(x, INFINITY);
    if (std::isinf(next)) return Value::floating(x - std::nextafter(x, -INFINITY));
    return Value::floating(next - x);
  });
}

}  // namespace lcm_control::xacro::py
