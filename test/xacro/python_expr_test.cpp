// The `${...}` expression evaluator: each construct family against CPython 3.11's values and str()/repr() output.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "xacro/python/python_expr.hpp"

namespace lcm_control::xacro {
namespace {

class MapNames : public Names {
 public:
  std::optional<Value> lookup(const std::string& name) const override {
    auto it = values.find(name);
    if (it == values.end()) return std::nullopt;
    return it->second;
  }
  std::map<std::string, Value> values;
};

MapNames& names() {
  static MapNames n = [] {
    MapNames m;
    m.values["x"] = Value::floating(0.5);
    m.values["l"] = Value::list({Value::integer(1), Value::integer(2), Value::integer(3)});
    m.values["s"] = Value::string("hello world");
    Dict d;
    d.set(Value::string("a"), Value::integer(1));
    d.set(Value::string("b"), Value::list({Value::floating(2.5)}));
    m.values["d"] = Value::dict(d);
    Dict kin;
    kin.attribute_access = true;
    kin.set(Value::string("shoulder"), Value::floating(0.1625));
    Dict cfg;
    cfg.attribute_access = true;
    cfg.set(Value::string("kinematics"), Value::dict(kin));
    cfg.set(Value::string("items"), Value::integer(7));
    m.values["cfg"] = Value::dict(cfg);
    Dict xacro;
    xacro.attribute_access = true;
    xacro.set(Value::string("arg"), Value::callable("xacro.arg", [](const List& args, const Kwargs&) {
                return Value::string("arg:" + str(args.at(0)));
              }));
    m.values["xacro"] = Value::dict(xacro);
    return m;
  }();
  return n;
}

std::string R(const std::string& expr) { return repr(evaluate(expr, names())); }
std::string S(const std::string& expr) { return str(evaluate(expr, names())); }
std::string Err(const std::string& expr) {
  try {
    return "no error: " + repr(evaluate(expr, names()));
  } catch (const EvalError& e) {
    return e.what();
  }
}

TEST(XacroValue, FloatReprAsPython) {
  EXPECT_EQ(float_repr(1e-5), "1e-05");
  EXPECT_EQ(float_repr(0.0001), "0.0001");
  EXPECT_EQ(float_repr(1e16), "1e+16");
  EXPECT_EQ(float_repr(1234567890123456.0), "1234567890123456.0");
  EXPECT_EQ(float_repr(100000.0), "100000.0");
  EXPECT_EQ(float_repr(-0.0), "-0.0");
  EXPECT_EQ(float_repr(1.0 / 0.0), "inf");
  EXPECT_EQ(float_repr(-1.0 / 0.0), "-inf");
  EXPECT_EQ(float_repr(std::nan("")), "nan");
  EXPECT_EQ(float_repr(0.1), "0.1");
  EXPECT_EQ(float_repr(3.141592653589793), "3.141592653589793");
  EXPECT_EQ(float_repr(2.5e-07), "2.5e-07");
  EXPECT_EQ(float_repr(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(float_repr(1e22), "1e+22");
  EXPECT_EQ(float_repr(1.5e300), "1.5e+300");
  EXPECT_EQ(float_repr(123456789012345678.0), "1.2345678901234568e+17");
  EXPECT_EQ(float_repr(9999999999999998.0), "9999999999999998.0");
  EXPECT_EQ(float_repr(5e-324), "5e-324");
  EXPECT_EQ(float_repr(1.7976931348623157e308), "1.7976931348623157e+308");
  EXPECT_EQ(float_repr(12345678.9), "12345678.9");
  EXPECT_EQ(float_repr(0.000123), "0.000123");
}

TEST(XacroValue, StrAndReprOfContainers) {
  EXPECT_EQ(R("[0.1, 'it\\'s', None, True]"), "[0.1, \"it's\", None, True]");
  EXPECT_EQ(S("[1, 'a', 0.5]"), "[1, 'a', 0.5]");
  EXPECT_EQ(S("{'a': (1,)}"), "{'a': (1,)}");
  EXPECT_EQ(S("(1, 2)"), "(1, 2)");
  EXPECT_EQ(S("()"), "()");
  EXPECT_EQ(S("'a'"), "a");
  EXPECT_EQ(R("'a'"), "'a'");
  EXPECT_EQ(R("'a\\tb\\nc\\\\'"), "'a\\tb\\nc\\\\'");
  EXPECT_EQ(S("None"), "None");
  EXPECT_EQ(S("False"), "False");
  EXPECT_TRUE(equal(Value::integer(1), Value::floating(1.0)));
  EXPECT_TRUE(equal(Value::boolean(true), Value::integer(1)));
  EXPECT_FALSE(equal(Value::list({}), Value::tuple({})));
  EXPECT_FALSE(truthy(Value::string("")));
  EXPECT_TRUE(truthy(Value::floating(-0.5)));
}

TEST(XacroExpr, NumberLiterals) {
  EXPECT_EQ(R("1."), "1.0");
  EXPECT_EQ(R(".5"), "0.5");
  EXPECT_EQ(R("1e-3"), "0.001");
  EXPECT_EQ(R("1E5"), "100000.0");
  EXPECT_EQ(R("1_000"), "1000");
  EXPECT_EQ(R("0x1F"), "31");
  EXPECT_EQ(R("0o17"), "15");
  EXPECT_EQ(R("0b101"), "5");
  EXPECT_EQ(R("-5"), "-5");
  EXPECT_EQ(R("1e400"), "inf");
  EXPECT_EQ(R("1e16"), "1e+16");
  EXPECT_EQ(R("1e15"), "1000000000000000.0");
}

TEST(XacroExpr, StringLiterals) {
  EXPECT_EQ(S("'it\\'s'"), "it's");
  EXPECT_EQ(S("\"say \\\"hi\\\"\""), "say \"hi\"");
  EXPECT_EQ(S("'a\\tb'"), "a\tb");
  EXPECT_EQ(S("'a' 'b'"), "ab");
  EXPECT_EQ(S("r'a\\nb'"), "a\\nb");
  EXPECT_EQ(S("'\\x41\\u00e9'"), "A\xc3\xa9");
}

TEST(XacroExpr, ContainerLiterals) {
  EXPECT_EQ(R("(1,)"), "(1,)");
  EXPECT_EQ(R("{'a': 1, 'b': [2, 3]}"), "{'a': 1, 'b': [2, 3]}");
  EXPECT_EQ(R("{}"), "{}");
  EXPECT_EQ(R("[1, 2,]"), "[1, 2]");
  EXPECT_EQ(R("1, 2"), "(1, 2)");
  EXPECT_EQ(R("dict(a=1, b=2)"), "{'a': 1, 'b': 2}");
  EXPECT_EQ(R("dict([('a', 1)])"), "{'a': 1}");
  EXPECT_EQ(R("dict(a=1)['a']"), "1");
  EXPECT_EQ(R("list((1, 2))"), "[1, 2]");
  EXPECT_EQ(R("list('abc')"), "['a', 'b', 'c']");
  EXPECT_EQ(R("tuple([1, 2])"), "(1, 2)");
}

TEST(XacroExpr, Arithmetic) {
  EXPECT_EQ(R("1 + 2 * 3"), "7");
  EXPECT_EQ(R("-2**2"), "-4");
  EXPECT_EQ(R("-3 ** 2"), "-9");
  EXPECT_EQ(R("(-8) ** 2"), "64");
  EXPECT_EQ(R("2**-1"), "0.5");
  EXPECT_EQ(R("2**3**2"), "512");
  EXPECT_EQ(R("2 ** 0.5"), "1.4142135623730951");
  EXPECT_EQ(R("10 ** 18"), "1000000000000000000");
  EXPECT_EQ(R("7 / 2"), "3.5");
  EXPECT_EQ(R("6 / 3"), "2.0");
  EXPECT_EQ(R("1 / 3"), "0.3333333333333333");
  EXPECT_EQ(R("3.0 * 1.1"), "3.3000000000000003");
  EXPECT_EQ(R("0.1 + 0.2"), "0.30000000000000004");
  EXPECT_EQ(R("1 + 2.0"), "3.0");
  EXPECT_EQ(R("True + 1"), "2");
  EXPECT_EQ(R("True * 2.5"), "2.5");
  EXPECT_EQ(R("x * 2"), "1.0");
  EXPECT_EQ(R("~5"), "-6");
  EXPECT_EQ(R("1 << 4"), "16");
  EXPECT_EQ(R("6 & 3"), "2");
  EXPECT_EQ(R("6 | 3"), "7");
  EXPECT_EQ(R("6 ^ 3"), "5");
}

TEST(XacroExpr, FloorDivisionAndModuloOfNegatives) {
  EXPECT_EQ(R("7 // 2"), "3");
  EXPECT_EQ(R("-7 // 2"), "-4");
  EXPECT_EQ(R("7 // -2"), "-4");
  EXPECT_EQ(R("-7 % 3"), "2");
  EXPECT_EQ(R("7 % -3"), "-2");
  EXPECT_EQ(R("-7.5 // 2"), "-4.0");
  EXPECT_EQ(R("-7.5 % 2"), "0.5");
  EXPECT_EQ(R("divmod(7, -2)"), "(-4, -1)");
}

TEST(XacroExpr, SequenceOperators) {
  EXPECT_EQ(R("'ab' * 3"), "'ababab'");
  EXPECT_EQ(R("3 * 'ab'"), "'ababab'");
  EXPECT_EQ(R("[1] * 2"), "[1, 1]");
  EXPECT_EQ(R("[1, 2] + [3]"), "[1, 2, 3]");
  EXPECT_EQ(R("(1, 2) + (3,)"), "(1, 2, 3)");
  EXPECT_EQ(R("'a' + 'b'"), "'ab'");
}

TEST(XacroExpr, Comparisons) {
  EXPECT_EQ(R("0 < 0.5 < 1"), "True");
  EXPECT_EQ(R("0 < x < 1"), "True");
  EXPECT_EQ(R("1 < 2 > 3"), "False");
  EXPECT_EQ(R("1 == 1.0 == True"), "True");
  EXPECT_EQ(R("1 < 2 == True"), "False");
  EXPECT_EQ(S("type(1.5)"), "<class 'float'>");
  EXPECT_EQ(S("len"), "<built-in function len>");
  EXPECT_EQ(R("not 1 == 2"), "True");
  EXPECT_EQ(R("[1, 2] < [1, 3]"), "True");
  EXPECT_EQ(R("(1, 2) == (1, 2)"), "True");
  EXPECT_EQ(R("[1, 2] == (1, 2)"), "False");
  EXPECT_EQ(R("'b' > 'a'"), "True");
  EXPECT_EQ(R("'x' in ['x']"), "True");
  EXPECT_EQ(R("'y' not in ['x']"), "True");
  EXPECT_EQ(R("'ell' in 'hello'"), "True");
  EXPECT_EQ(R("'a' in {'a': 1}"), "True");
  EXPECT_EQ(R("None is None"), "True");
  EXPECT_EQ(R("1 is not None"), "True");
  EXPECT_EQ(R("type(1) == int"), "True");
  EXPECT_EQ(R("type('a') is str"), "True");
}

TEST(XacroExpr, BooleanOperatorsReturnOperands) {
  EXPECT_EQ(R("'' or 'x'"), "'x'");
  EXPECT_EQ(R("0 and 1/0"), "0");
  EXPECT_EQ(R("'a' and 'b'"), "'b'");
  EXPECT_EQ(R("None or 0"), "0");
  EXPECT_EQ(R("not 0"), "True");
  EXPECT_EQ(R("not []"), "True");
  EXPECT_EQ(R("1 if False else 2"), "2");
  EXPECT_EQ(R("1 if True else 2"), "1");
  EXPECT_EQ(R("1 if x > 1 else 2 if x > 0 else 3"), "2");
}

TEST(XacroExpr, NamesAttributesAndIndexing) {
  EXPECT_EQ(R("d['a']"), "1");
  EXPECT_EQ(R("d['b'][0]"), "2.5");
  EXPECT_EQ(R("l[-1]"), "3");
  EXPECT_EQ(R("s.split()[1]"), "'world'");
  EXPECT_EQ(R("cfg.kinematics.shoulder"), "0.1625");
  EXPECT_EQ(R("cfg['kinematics']['shoulder']"), "0.1625");
  EXPECT_EQ(R("xacro.arg('prefix')"), "'arg:prefix'");
  EXPECT_EQ(S("cfg.items()"), "[('kinematics', {'shoulder': 0.1625}), ('items', 7)]");  // a method before a key
  EXPECT_EQ(R("cfg['items']"), "7");
}

TEST(XacroExpr, NamesShadowBuiltins) {
  EXPECT_EQ(R("pi"), "3.141592653589793");
  MapNames local;
  local.values["pi"] = Value::integer(3);
  EXPECT_EQ(repr(evaluate("pi * 2", local)), "6");
  EXPECT_EQ(repr(evaluate("math.pi", local)), "3.141592653589793");
}

TEST(XacroExpr, Slicing) {
  EXPECT_EQ(R("'abc'[1:3]"), "'bc'");
  EXPECT_EQ(R("[1, 2, 3][::-1]"), "[3, 2, 1]");
  EXPECT_EQ(R("'abc'[:2]"), "'ab'");
  EXPECT_EQ(R("'abcdef'[::2]"), "'ace'");
  EXPECT_EQ(R("'abcdef'[-2:]"), "'ef'");
  EXPECT_EQ(R("'abcdef'[1:-1]"), "'bcde'");
  EXPECT_EQ(R("'abcdef'[4:1:-1]"), "'edc'");
  EXPECT_EQ(R("[1, 2, 3][5:]"), "[]");
  EXPECT_EQ(R("'hello'[10:20]"), "''");
  EXPECT_EQ(R("(1, 2, 3)[1:]"), "(2, 3)");
}

TEST(XacroExpr, StringMethods) {
  EXPECT_EQ(R("'a b'.split()[0]"), "'a'");
  EXPECT_EQ(R("'  a  b  '.split()"), "['a', 'b']");
  EXPECT_EQ(R("'a,b,,c'.split(',')"), "['a', 'b', '', 'c']");
  EXPECT_EQ(R("'a b c'.split(' ', 1)"), "['a', 'b c']");
  EXPECT_EQ(R("'a b c'.rsplit(' ', 1)"), "['a b', 'c']");
  EXPECT_EQ(R("'a b c d'.split(maxsplit=2)"), "['a', 'b', 'c d']");
  EXPECT_EQ(R("'-'.join(['a', 'b'])"), "'a-b'");
  EXPECT_EQ(R("'Hello'.upper()"), "'HELLO'");
  EXPECT_EQ(R("'Hello'.lower()"), "'hello'");
  EXPECT_EQ(R("'aXbX'.replace('X', 'y')"), "'ayby'");
  EXPECT_EQ(R("'aXbX'.replace('X', 'y', 1)"), "'aybX'");
  EXPECT_EQ(R("'file.xacro'.endswith('.xacro')"), "True");
  EXPECT_EQ(R("'file.urdf'.endswith(('.xacro', '.urdf'))"), "True");
  EXPECT_EQ(R("'prefix_x'.startswith('prefix')"), "True");
  EXPECT_EQ(R("'  x '.strip()"), "'x'");
  EXPECT_EQ(R("'xxaxx'.strip('x')"), "'a'");
  EXPECT_EQ(R("'  x '.lstrip()"), "'x '");
  EXPECT_EQ(R("'  x '.rstrip()"), "'  x'");
  EXPECT_EQ(R("'hello'.find('l')"), "2");
  EXPECT_EQ(R("'hello'.rfind('l')"), "3");
  EXPECT_EQ(R("'hello'.find('z')"), "-1");
  EXPECT_EQ(R("'hello'.count('l')"), "2");
  EXPECT_EQ(R("'hello world'.title()"), "'Hello World'");
  EXPECT_EQ(R("'hello'.capitalize()"), "'Hello'");
}

TEST(XacroExpr, StrFormat) {
  EXPECT_EQ(S("'{}-{:.2f}'.format('x', 1.005)"), "x-1.00");
  EXPECT_EQ(S("'{0}{1}{0}'.format('a', 'b')"), "aba");
  EXPECT_EQ(S("'{name}!'.format(name='x')"), "x!");
  EXPECT_EQ(S("'{:>5}|{:<5}|{:^5}'.format('a', 'b', 'c')"), "    a|b    |  c  ");
  EXPECT_EQ(S("'{:05.1f}'.format(3.14159)"), "003.1");
  EXPECT_EQ(S("'{:+d}'.format(5)"), "+5");
  EXPECT_EQ(S("'{:,}'.format(1234567)"), "1,234,567");
  EXPECT_EQ(S("'{:.3e}'.format(12345.678)"), "1.235e+04");
  EXPECT_EQ(S("'{:g}'.format(0.0001)"), "0.0001");
  EXPECT_EQ(S("'{:.2%}'.format(0.256)"), "25.60%");
  EXPECT_EQ(S("'{:x}'.format(255)"), "ff");
  EXPECT_EQ(S("'{!r}'.format('a')"), "'a'");
  EXPECT_EQ(S("'{:.3}'.format(1.0)"), "1.0");
  EXPECT_EQ(S("'{}'.format(0.1)"), "0.1");
  EXPECT_EQ(S("'{:.0f}'.format(2.5)"), "2");
  EXPECT_EQ(S("'{:.2f}'.format(2.675)"), "2.67");
}

TEST(XacroExpr, PercentFormatAndFStrings) {
  EXPECT_EQ(S("'%s and %d' % ('a', 3)"), "a and 3");
  EXPECT_EQ(S("'%.3f' % 3.14159"), "3.142");
  EXPECT_EQ(S("'%5.1f|%-5d|' % (2.25, 3)"), "  2.2|3    |");
  EXPECT_EQ(S("'%s' % [1, 2]"), "[1, 2]");
  EXPECT_EQ(S("'%x' % 255"), "ff");
  EXPECT_EQ(S("'%g' % 1e-5"), "1e-05");
  EXPECT_EQ(S("'%03d' % 7"), "007");
  EXPECT_EQ(S("'%(a)s' % {'a': 'z'}"), "z");
  EXPECT_EQ(S("f'{1 + 1}'"), "2");
  EXPECT_EQ(S("f'{x:.2f} and {s!r}'"), "0.50 and 'hello world'");
  EXPECT_EQ(S("f'{{}} {l}'"), "{} [1, 2, 3]");
}

TEST(XacroExpr, ListAndDictMethods) {
  EXPECT_EQ(R("[1, 2, 3].index(2)"), "1");
  EXPECT_EQ(R("[1, 2, 2].count(2)"), "2");
  EXPECT_EQ(R("{'a': 1}.get('a')"), "1");
  EXPECT_EQ(R("{'a': 1}.get('b')"), "None");
  EXPECT_EQ(R("{'a': 1}.get('b', 5)"), "5");
  EXPECT_EQ(R("list({'a': 1, 'b': 2}.keys())"), "['a', 'b']");
  EXPECT_EQ(R("list({'a': 1, 'b': 2}.values())"), "[1, 2]");
  EXPECT_EQ(R("list({'a': 1, 'b': 2}.items())"), "[('a', 1), ('b', 2)]");
}

TEST(XacroExpr, Builtins) {
  EXPECT_EQ(R("len('abc')"), "3");
  EXPECT_EQ(R("len([1, 2])"), "2");
  EXPECT_EQ(R("len({'a': 1})"), "1");
  EXPECT_EQ(R("min(3, 1, 2)"), "1");
  EXPECT_EQ(R("min([3, 1, 2])"), "1");
  EXPECT_EQ(R("max([0.5, 2])"), "2");
  EXPECT_EQ(R("max('abc')"), "'c'");
  EXPECT_EQ(R("abs(-3)"), "3");
  EXPECT_EQ(R("abs(-2.5)"), "2.5");
  EXPECT_EQ(R("int('42')"), "42");
  EXPECT_EQ(R("int(' -7 ')"), "-7");
  EXPECT_EQ(R("int(3.9)"), "3");
  EXPECT_EQ(R("int(-3.9)"), "-3");
  EXPECT_EQ(R("int(True)"), "1");
  EXPECT_EQ(R("int('1_000')"), "1000");
  EXPECT_EQ(R("float('1.5')"), "1.5");
  EXPECT_EQ(R("float('inf')"), "inf");
  EXPECT_EQ(R("float('-inf')"), "-inf");
  EXPECT_EQ(R("float(' 2 ')"), "2.0");
  EXPECT_EQ(R("float(3)"), "3.0");
  EXPECT_EQ(R("str(1.0)"), "'1.0'");
  EXPECT_EQ(R("str(True)"), "'True'");
  EXPECT_EQ(R("str([1, 'a'])"), "\"[1, 'a']\"");
  EXPECT_EQ(R("bool(0)"), "False");
  EXPECT_EQ(R("bool('x')"), "True");
  EXPECT_EQ(R("sorted([3, 1, 2])"), "[1, 2, 3]");
  EXPECT_EQ(R("sorted([3, 1, 2], reverse=True)"), "[3, 2, 1]");
  EXPECT_EQ(R("sorted([(1, 'b'), (0, 'c')], key=lambda t: t[1])"), "[(1, 'b'), (0, 'c')]");
  EXPECT_EQ(R("list(range(3))"), "[0, 1, 2]");
  EXPECT_EQ(R("list(range(1, 7, 2))"), "[1, 3, 5]");
  EXPECT_EQ(R("list(range(5, 0, -2))"), "[5, 3, 1]");
  EXPECT_EQ(R("sum([1, 2, 3])"), "6");
  EXPECT_EQ(R("sum([0.1, 0.2, 0.3])"), "0.6000000000000001");
  EXPECT_EQ(R("sum([1, 2], 10)"), "13");
  EXPECT_EQ(R("any([0, 1])"), "True");
  EXPECT_EQ(R("all([1, 0])"), "False");
  EXPECT_EQ(R("all([])"), "True");
  EXPECT_EQ(R("list(zip([1, 2], ['a', 'b']))"), "[(1, 'a'), (2, 'b')]");
  EXPECT_EQ(R("list(map(float, ['1', '2.5']))"), "[1.0, 2.5]");
  EXPECT_EQ(R("list(enumerate(['a', 'b']))"), "[(0, 'a'), (1, 'b')]");
  EXPECT_EQ(R("repr('x')"), "\"'x'\"");
  EXPECT_EQ(R("isinstance(1, int)"), "True");
  EXPECT_EQ(R("isinstance(1.0, (int, float))"), "True");
  EXPECT_EQ(R("isinstance(True, int)"), "True");
  EXPECT_EQ(R("isinstance('a', str)"), "True");
  EXPECT_EQ(R("isinstance(1, float)"), "False");
  EXPECT_EQ(R("python.abs(-1)"), "1");
}

TEST(XacroExpr, RoundHalfEven) {
  EXPECT_EQ(R("round(2.5)"), "2");
  EXPECT_EQ(R("round(3.5)"), "4");
  EXPECT_EQ(R("round(-2.5)"), "-2");
  EXPECT_EQ(R("round(0.5)"), "0");
  EXPECT_EQ(R("round(-0.5)"), "0");
  EXPECT_EQ(R("round(2.675, 2)"), "2.67");
  EXPECT_EQ(R("round(0.125, 2)"), "0.12");
  EXPECT_EQ(R("round(1234.5678, -2)"), "1200.0");
  EXPECT_EQ(R("round(1.5, 0)"), "2.0");
  EXPECT_EQ(R("round(2.5, 0)"), "2.0");
  EXPECT_EQ(R("round(15, -1)"), "20");
  EXPECT_EQ(R("round(25, -1)"), "20");
}

TEST(XacroExpr, Math) {
  EXPECT_EQ(R("e"), "2.718281828459045");
  EXPECT_EQ(R("inf"), "inf");
  EXPECT_EQ(R("tau"), "6.283185307179586");
  EXPECT_EQ(R("sin(pi / 2)"), "1.0");
  EXPECT_EQ(R("cos(0)"), "1.0");
  EXPECT_EQ(R("radians(180)"), "3.141592653589793");
  EXPECT_EQ(R("degrees(pi)"), "180.0");
  EXPECT_EQ(R("sqrt(2)"), "1.4142135623730951");
  EXPECT_EQ(R("atan2(1, 1)"), "0.7853981633974483");
  EXPECT_EQ(R("fabs(-1)"), "1.0");
  EXPECT_EQ(R("floor(2.5)"), "2");
  EXPECT_EQ(R("floor(-2.5)"), "-3");
  EXPECT_EQ(R("ceil(2.1)"), "3");
  EXPECT_EQ(R("pow(2, 3)"), "8.0");
  EXPECT_EQ(R("exp(1)"), "2.718281828459045");
  EXPECT_EQ(R("log(e)"), "1.0");
  EXPECT_EQ(R("log(8, 2)"), "3.0");
  EXPECT_EQ(R("log10(1000)"), "3.0");
  EXPECT_EQ(R("hypot(3, 4)"), "5.0");
  EXPECT_EQ(R("tan(0.5)"), "0.5463024898437905");
  EXPECT_EQ(R("acos(0.5)"), "1.0471975511965979");
  EXPECT_EQ(R("asin(1)"), "1.5707963267948966");
  EXPECT_EQ(R("math.sqrt(16)"), "4.0");
  EXPECT_EQ(R("math.radians(90)"), "1.5707963267948966");
  EXPECT_EQ(R("math.floor(3.7)"), "3");
  EXPECT_EQ(R("math.isclose(1.0, 1.0000000001)"), "True");
  EXPECT_EQ(R("math.copysign(1, -0.0)"), "-1.0");
  EXPECT_EQ(R("math.fmod(7, 3)"), "1.0");
  EXPECT_EQ(R("math.trunc(-2.5)"), "-2");
  EXPECT_EQ(R("math.factorial(5)"), "120");
  EXPECT_EQ(R("math.gcd(12, 18)"), "6");
}

TEST(XacroExpr, ComprehensionsAndLambdas) {
  EXPECT_EQ(R("[v * 2 for v in l]"), "[2, 4, 6]");
  EXPECT_EQ(R("[v for v in l if v > 1]"), "[2, 3]");
  EXPECT_EQ(R("[a + b for a in 'ab' for b in 'xy']"), "['ax', 'ay', 'bx', 'by']");
  EXPECT_EQ(R("{k: v for k, v in [('a', 1)]}"), "{'a': 1}");
  EXPECT_EQ(R("sum(v for v in l)"), "6");
  EXPECT_EQ(R("any(v > 2 for v in l)"), "True");
  EXPECT_EQ(R("(lambda a, b: a * b)(3, 4)"), "12");
  EXPECT_EQ(R("list(map(lambda v: v * 2, [1, 2]))"), "[2, 4]");
  EXPECT_EQ(R("[k for k, v in d.items()]"), "['a', 'b']");
}

TEST(XacroExprErrors, NameTypeKeyIndexAttribute) {
  EXPECT_EQ(Err("foo + 1"), "NameError: name 'foo' is not defined");
  EXPECT_EQ(Err("1 + 'a'"), "TypeError: unsupported operand type(s) for +: 'int' and 'str'");
  EXPECT_EQ(Err("'a' + 1"), "TypeError: can only concatenate str (not \"int\") to str");
  EXPECT_EQ(Err("'a' * 1.5"), "TypeError: can't multiply sequence by non-int of type 'float'");
  EXPECT_EQ(Err("-'a'"), "TypeError: bad operand type for unary -: 'str'");
  EXPECT_EQ(Err("1 < 'a'"), "TypeError: '<' not supported between instances of 'int' and 'str'");
  EXPECT_EQ(Err("len(1)"), "TypeError: object of type 'int' has no len()");
  EXPECT_EQ(Err("1()"), "TypeError: 'int' object is not callable");
  EXPECT_EQ(Err("1 in 1"), "TypeError: argument of type 'int' is not iterable");
  EXPECT_EQ(Err("'a'.join([1])"), "TypeError: sequence item 0: expected str instance, int found");
  EXPECT_EQ(Err("{'a': 1}['k']"), "KeyError: 'k'");
  EXPECT_EQ(Err("'{x}'.format(y=1)"), "KeyError: 'x'");
  EXPECT_EQ(Err("[1, 2][5]"), "IndexError: list index out of range");
  EXPECT_EQ(Err("(1,)[3]"), "IndexError: tuple index out of range");
  EXPECT_EQ(Err("'ab'[5]"), "IndexError: string index out of range");
  EXPECT_EQ(Err("[1]['a']"), "TypeError: list indices must be integers or slices, not str");
  EXPECT_EQ(Err("{'a': 1}.x"), "AttributeError: 'dict' object has no attribute 'x'");
  EXPECT_EQ(Err("d.a"), "AttributeError: 'dict' object has no attribute 'a'");
  EXPECT_EQ(Err("cfg.nope"), "AttributeError: The yaml dictionary has no key 'nope'");
  EXPECT_EQ(Err("'a'.nope"), "AttributeError: 'str' object has no attribute 'nope'");
  EXPECT_EQ(Err("math.nope"), "AttributeError: module 'math' has no attribute 'nope'");
}

TEST(XacroExprErrors, ArithmeticAndValue) {
  EXPECT_EQ(Err("1 / 0"), "ZeroDivisionError: division by zero");
  EXPECT_EQ(Err("1 // 0"), "ZeroDivisionError: integer division or modulo by zero");
  EXPECT_EQ(Err("1 % 0"), "ZeroDivisionError: integer modulo by zero");
  EXPECT_EQ(Err("1.0 / 0"), "ZeroDivisionError: float division by zero");
  EXPECT_EQ(Err("0 ** -1"), "ZeroDivisionError: 0.0 cannot be raised to a negative power");
  EXPECT_EQ(Err("sqrt(-1)"), "ValueError: math domain error");
  EXPECT_EQ(Err("log(0)"), "ValueError: math domain error");
  EXPECT_EQ(Err("acos(2)"), "ValueError: math domain error");
  EXPECT_EQ(Err("exp(1000)"), "OverflowError: math range error");
  EXPECT_EQ(Err("math.floor(inf)"), "OverflowError: cannot convert float infinity to integer");
  EXPECT_EQ(Err("int('abc')"), "ValueError: invalid literal for int() with base 10: 'abc'");
  EXPECT_EQ(Err("float('abc')"), "ValueError: could not convert string to float: 'abc'");
  EXPECT_EQ(Err("max([])"), "ValueError: max() arg is an empty sequence");
  EXPECT_EQ(Err("[1, 2].index(5)"), "ValueError: 5 is not in list");
  EXPECT_EQ(Err("'%s %s' % ('a',)"), "TypeError: not enough arguments for format string");
  EXPECT_EQ(Err("'{} {}'.format(1)"), "IndexError: Replacement index 1 out of range for positional args tuple");
}

TEST(XacroExprErrors, SyntaxSaysWhatAndWhere) {
  EXPECT_EQ(Err("1 +"), "SyntaxError: invalid syntax: unexpected end of expression at column 4");
  EXPECT_EQ(Err("1 2"), "SyntaxError: invalid syntax: unexpected literal at column 3");
  EXPECT_EQ(Err("f(,)"), "SyntaxError: invalid syntax: unexpected ',' at column 3");
  EXPECT_EQ(Err("a = 1"), "SyntaxError: invalid syntax: unexpected '=' at column 3");
  EXPECT_EQ(Err("(1 +"), "SyntaxError: '(' was never closed (column 1)");
  EXPECT_EQ(Err("[1, 2"), "SyntaxError: '[' was never closed (column 1)");
  EXPECT_EQ(Err(")"), "SyntaxError: unmatched ')' at column 1");
  EXPECT_EQ(Err("'abc"), "SyntaxError: unterminated string literal (column 1)");
  EXPECT_EQ(Err("1 if 2"), "SyntaxError: expected 'else' after 'if' expression (column 7)");
  EXPECT_EQ(Err("01"), "SyntaxError: leading zeros in decimal integer literals are not permitted; use an 0o "
                       "prefix for octal integers (column 1)");
  EXPECT_EQ(Err("1 $ 2"), "SyntaxError: invalid character '$' at column 3");
  EXPECT_EQ(Err(""), "SyntaxError: invalid syntax: unexpected end of expression at column 1");
}

TEST(XacroExpr, RepeatedExpressionsUseTheCacheAndStillSeeCurrentNames) {
  MapNames a;
  a.values["v"] = Value::integer(1);
  MapNames b;
  b.values["v"] = Value::string("z");
  EXPECT_EQ(repr(evaluate("v * 2", a)), "2");
  EXPECT_EQ(repr(evaluate("v * 2", b)), "'zz'");
  EXPECT_EQ(repr(evaluate(" v * 2 ", a)), "2");
}

}  // namespace
}  // namespace lcm_control::xacro

namespace lcm_control::xacro {
namespace {

// Strings are code points, as Python's str (issue 51: 'é'[0] wrote a lone byte, len('é') was 2); case mapping covers
// ASCII, Latin-1, Greek and Cyrillic (the guide's xacro section states it).
TEST(XacroExpr, StringsAreMeasuredIndexedSlicedAndCaseMappedByCodePoint) {
  EXPECT_EQ(S("len('é')"), "1");
  EXPECT_EQ(S("len('naïve-Ω')"), "7");
  EXPECT_EQ(S("'héllo'[1]"), "é");
  EXPECT_EQ(S("'héllo'[-4]"), "é");
  EXPECT_EQ(S("'héllo'[1:3]"), "él");
  EXPECT_EQ(S("'héllo'[::-1]"), "olléh");
  EXPECT_EQ(S("'é'.upper()"), "É");
  EXPECT_EQ(S("'ΑΒΓ Ω'.lower()"), "αβγ ω");
  EXPECT_EQ(S("'привет'.upper()"), "ПРИВЕТ");
  EXPECT_EQ(S("'élan vital'.title()"), "Élan Vital");
  EXPECT_EQ(S("'ÉCOLE'.capitalize()"), "École");
  EXPECT_EQ(S("'xéy'.find('y')"), "2");
  EXPECT_EQ(S("'éaéa'.rfind('a', 0, 2)"), "1");
  EXPECT_EQ(S("'ab'.upper() + 'AB'.lower()"), "ABab");
  EXPECT_EQ(S("'é'.zfill(3)"), "00é");
  EXPECT_NE(Err("'é'[1]").find("IndexError"), std::string::npos) << Err("'é'[1]");
}

}  // namespace
}  // namespace lcm_control::xacro
