#include "control/expression.hpp"

#include <fmt/format.h>
#include <muParser.h>

#include <cmath>

namespace lcm_control {

namespace {
double floored_mod(double a, double b) { return a - b * std::floor(a / b); }  // mod(-1, 3) = 2, as a period wants
}  // namespace

Expressions::Expressions(const std::vector<std::string>& texts) : texts_(texts) {
  if (texts.empty()) throw ExpressionError("no expression given");
  for (const auto& text : texts) {
    auto p = std::make_unique<mu::Parser>();
    try {
      p->DefineVar("i", &i_);
      p->DefineVar("t", &t_);
      p->DefineConst("pi", M_PI);
      p->DefineFun("mod", floored_mod);
      p->SetExpr(text);
      p->Eval();
    } catch (const mu::Parser::exception_type& e) {
      throw ExpressionError(
          fmt::format("expression '{}': {} (variables: i, t; constants: pi, _pi, _e; functions: muparser's and mod(a, b))", text, e.GetMsg()));
    }
    parsers_.push_back(std::move(p));
  }
}

Expressions::~Expressions() = default;

int Expressions::eval(int64_t i, double t, double* out) {
  i_ = static_cast<double>(i);
  t_ = t;
  int bad = -1;
  for (size_t k = 0; k < parsers_.size(); ++k) {
    double x = NAN;
    try {
      x = parsers_[k]->Eval();
    } catch (const mu::Parser::exception_type&) {
    }
    out[k] = x;
    if (bad < 0 && !std::isfinite(x)) bad = static_cast<int>(k);
  }
  return bad;
}

void Expressions::eval_checked(int64_t i, double t, double* out) {
  const int bad = eval(i, t, out);
  if (bad >= 0)
    throw ExpressionError(fmt::format("expression '{}' is {} at i={} t={:g}; nothing sent for it", texts_[bad],
                                      out[bad], i, t));
}

}  // namespace lcm_control
