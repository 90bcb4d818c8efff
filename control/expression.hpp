// muparser expressions in i (tick count) and t (seconds), shared by turret-cmd
// and the controller manager's command sources. Parsing checks every expression
// once (one error naming it); evaluation writes into a caller's buffer and does
// not allocate, so it may run on the control loop.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace mu {
class Parser;
}

namespace lcm_control {

class ExpressionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Expressions {
 public:
  // Throws ExpressionError "expression 'TEXT': WHY (variables: i, t; ...)".
  explicit Expressions(const std::vector<std::string>& texts);
  ~Expressions();
  Expressions(const Expressions&) = delete;
  Expressions& operator=(const Expressions&) = delete;

  size_t size() const { return texts_.size(); }
  const std::vector<std::string>& texts() const { return texts_; }

  // out[k] = expression k at (i, t); out must hold size() values. Returns the
  // index of the first value that is NaN or Inf (or a muparser failure), else -1.
  int eval(int64_t i, double t, double* out);
  // eval() that throws ExpressionError naming the expression, i and t.
  void eval_checked(int64_t i, double t, double* out);

 private:
  std::vector<std::string> texts_;
  std::vector<std::unique_ptr<mu::Parser>> parsers_;
  double i_ = 0, t_ = 0;
};

}  // namespace lcm_control
