// The `${...}` expression evaluator: each construct family against CPython's values and str() output.
#include <gtest/gtest.h>

#include <map>

#include "description/xacro/python_expr.hpp"

namespace lcm_control::xacro {
namespace {

TEST(XacroValue, FloatRepr) {
  EXPECT_EQ(float_repr(0.1), "0.1");
  EXPECT_EQ(float_repr(1e-5), "1e-05");
}

}  // namespace
}  // namespace lcm_control::xacro
