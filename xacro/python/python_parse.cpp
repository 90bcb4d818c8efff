// The tokenizer and recursive-descent parser of xacro's Python expression subset (see python_ast.hpp).
#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "xacro/budget.hpp"
#include "xacro/python/python_ast.hpp"

#include "xacro/python/utf8.hpp"

namespace lcm_control::xacro::ast {

namespace {

enum class Tok { End, Name, Number, String, FString, Op };

struct Token {
  Tok kind = Tok::End;
  std::string text;  // Name, Op; FString: the raw body
  Value value;       // Number, String
  int column = 1;
};

[[noreturn]] void syntax_error(const std::string& message) { throw EvalError("SyntaxError", message); }

bool is_name_start(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || static_cast<unsigned char>(c) >= 0x80;
}
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_name_char(char c) { return is_name_start(c) || is_digit(c); }


class Lexer {
 public:
  explicit Lexer(std::string_view s) : s_(s) {}

  std::vector<Token> run() {
    std::vector<Token> out;
    while (true) {
      while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r' ||
                                s_[i_] == '\f' || (s_[i_] == '\\' && i_ + 1 < s_.size() && s_[i_ + 1] == '\n')))
        ++i_;
      Token t;
      t.column = static_cast<int>(i_) + 1;
      if (i_ >= s_.size()) {
        out.push_back(std::move(t));
        return out;
      }
      const char c = s_[i_];
      if (is_digit(c) || (c == '.' && i_ + 1 < s_.size() && is_digit(s_[i_ + 1]))) {
        number(t);
      } else if (is_name_start(c)) {
        size_t j = i_;
        while (j < s_.size() && is_name_char(s_[j])) ++j;
        const std::string_view word = s_.substr(i_, j - i_);
        if (j < s_.size() && (s_[j] == '\'' || s_[j] == '"') && word.size() <= 2 && string_prefix(word)) {
          i_ = j;
          string(t, word);
        } else {
          t.kind = Tok::Name;
          t.text = std::string(word);
          i_ = j;
        }
      } else if (c == '\'' || c == '"') {
        string(t, "");
      } else {
        static const char* const two[] = {"**", "//", "==", "!=", "<=", ">=", "<<", ">>", "->", ":="};
        t.kind = Tok::Op;
        for (const char* op : two)
          if (s_.substr(i_, 2) == op) t.text = op;
        if (t.text.empty()) {
          if (!std::strchr("+-*/%<>()[]{},:.~&|^=@", c))
            syntax_error(fmt::format("invalid character '{}' at column {}", c, t.column));
          t.text = std::string(1, c);
        }
        i_ += t.text.size();
      }
      out.push_back(std::move(t));
    }
  }

 private:
  static bool string_prefix(std::string_view w) {
    for (char c : w)
      if (!std::strchr("rRbBuUfF", c)) return false;
    return true;
  }

  void number(Token& t) {
    const size_t start = i_;
    t.kind = Tok::Number;
    auto digits = [&](auto pred) {
      std::string d;
      while (i_ < s_.size() && (pred(s_[i_]) || (s_[i_] == '_' && i_ + 1 < s_.size() && pred(s_[i_ + 1])))) {
        if (s_[i_] != '_') d += s_[i_];
        ++i_;
      }
      return d;
    };
    if (s_[i_] == '0' && i_ + 1 < s_.size() && std::strchr("xXoObB", s_[i_ + 1])) {
      const char base_char = static_cast<char>(s_[i_ + 1] | 0x20);
      const int base = base_char == 'x' ? 16 : base_char == 'o' ? 8 : 2;
      i_ += 2;
      if (i_ < s_.size() && s_[i_] == '_') ++i_;
      const std::string d = digits([base](char ch) {
        if (base == 16) return std::isxdigit(static_cast<unsigned char>(ch)) != 0;
        return ch >= '0' && ch < '0' + base;
      });
      if (d.empty()) syntax_error(fmt::format("invalid number literal at column {}", t.column));
      errno = 0;
      const unsigned long long v = std::strtoull(d.c_str(), nullptr, base);
      if (errno == ERANGE || v > static_cast<unsigned long long>(INT64_MAX))
        syntax_error(fmt::format("integer literal too large at column {}", t.column));
      t.value = Value::integer(static_cast<int64_t>(v));
    } else {
      std::string text = digits(is_digit);
      bool is_float = false;
      if (i_ < s_.size() && s_[i_] == '.') {
        ++i_;
        is_float = true;
        text += '.' + digits(is_digit);
      }
      if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
        size_t j = i_ + 1;
        if (j < s_.size() && (s_[j] == '+' || s_[j] == '-')) ++j;
        if (j < s_.size() && is_digit(s_[j])) {
          text += 'e';
          if (s_[i_ + 1] == '-') text += '-';
          i_ = j;
          text += digits(is_digit);
          is_float = true;
        }
      }
      if (i_ < s_.size() && (s_[i_] == 'j' || s_[i_] == 'J'))
        syntax_error(fmt::format("complex numbers are not supported (column {})", t.column));
      if (is_float) {
        t.value = Value::floating(std::strtod(text.c_str(), nullptr));
      } else {
        if (text.size() > 1 && text[0] == '0' && text.find_first_not_of('0') != std::string::npos)
          syntax_error(fmt::format(
              "leading zeros in decimal integer literals are not permitted; use an 0o prefix for octal integers "
              "(column {})",
              t.column));
        errno = 0;
        const long long v = std::strtoll(text.c_str(), nullptr, 10);
        if (errno == ERANGE) syntax_error(fmt::format("integer literal too large at column {}", t.column));
        t.value = Value::integer(v);
      }
    }
    if (i_ < s_.size() && is_name_char(s_[i_]))
      syntax_error(fmt::format("invalid decimal literal at column {}", static_cast<int>(start) + 1));
  }

  void string(Token& t, std::string_view prefix) {
    bool raw = false, f = false;
    for (char c : prefix) {
      raw = raw || c == 'r' || c == 'R';
      f = f || c == 'f' || c == 'F';
    }
    const char q = s_[i_];
    const bool triple = s_.substr(i_, 3) == std::string(3, q);
    i_ += triple ? 3 : 1;
    std::string out;
    while (true) {
      if (i_ >= s_.size() || (!triple && s_[i_] == '\n'))
        syntax_error(fmt::format("unterminated string literal (column {})", t.column));
      const char c = s_[i_];
      if (c == q && (!triple || s_.substr(i_, 3) == std::string(3, q))) {
        i_ += triple ? 3 : 1;
        break;
      }
      if (c == '\\' && i_ + 1 < s_.size()) {
        const char n = s_[i_ + 1];
        if (raw || f) {
          if (f && !raw) {
            escape(out, n);
          } else {
            out += c;
            out += n;
            i_ += 2;
          }
          continue;
        }
        escape(out, n);
        continue;
      }
      out += c;
      ++i_;
    }
    if (f) {
      t.kind = Tok::FString;
      t.text = std::move(out);
    } else {
      t.kind = Tok::String;
      t.value = Value::string(std::move(out));
    }
  }

  void escape(std::string& out, char n) {
    i_ += 2;
    switch (n) {
      case '\n': return;
      case 'n': out += '\n'; return;
      case 't': out += '\t'; return;
      case 'r': out += '\r'; return;
      case '\\': out += '\\'; return;
      case '\'': out += '\''; return;
      case '"': out += '"'; return;
      case 'a': out += '\a'; return;
      case 'b': out += '\b'; return;
      case 'f': out += '\f'; return;
      case 'v': out += '\v'; return;
      case 'x':
      case 'u':
      case 'U': {
        const size_t len = n == 'x' ? 2 : n == 'u' ? 4 : 8;
        const std::string hex(s_.substr(i_, len));
        if (hex.size() != len || hex.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
          syntax_error(fmt::format("truncated \\{} escape at column {}", n, static_cast<int>(i_) - 1));
        i_ += len;
        append_utf8(out, static_cast<uint32_t>(std::strtoul(hex.c_str(), nullptr, 16)));
        return;
      }
      default:
        if (n >= '0' && n <= '7') {
          uint32_t v = 0;
          size_t k = i_ - 1;
          for (int d = 0; d < 3 && k < s_.size() && s_[k] >= '0' && s_[k] <= '7'; ++d, ++k) v = v * 8 + (s_[k] - '0');
          i_ = k;
          append_utf8(out, v);
          return;
        }
        out += '\\';
        out += n;
    }
  }

  std::string_view s_;
  size_t i_ = 0;
};

NodePtr make_const(Value v, int column) {
  auto n = std::make_shared<Node>();
  n->value = std::move(v);
  n->column = column;
  return n;
}

class Parser {
 public:
  explicit Parser(std::string_view text) : toks_(Lexer(text).run()) {}

  // How deep the evaluator will recurse: parentheses, brackets and calls (each test()), unary operators, `not`, `**`,
  // and each operator of a chain (a+b+c holds a+b in the outer +). Refused far below what a thread's stack takes.
  static constexpr int kMaxDepth = 400;

  NodePtr run() {
    NodePtr n = testlist(/*allow_trailing_comma=*/true);
    if (peek().kind != Tok::End) unexpected();
    return n;
  }

 private:
  const Token& peek(size_t ahead = 0) const { return toks_[std::min(pos_ + ahead, toks_.size() - 1)]; }
  const Token& next() {
    const Token& t = toks_[pos_];
    if (pos_ + 1 < toks_.size()) ++pos_;
    return t;
  }
  bool is_op(const char* op, size_t ahead = 0) const {
    const Token& t = peek(ahead);
    return t.kind == Tok::Op && t.text == op;
  }
  bool is_kw(const char* kw, size_t ahead = 0) const {
    const Token& t = peek(ahead);
    return t.kind == Tok::Name && t.text == kw;
  }
  const Token& opening() {
    const Token& t = next();
    open_.push_back(&t);
    return t;
  }
  bool accept_op(const char* op) {
    if (!is_op(op)) return false;
    next();
    return true;
  }
  bool accept_kw(const char* kw) {
    if (!is_kw(kw)) return false;
    next();
    return true;
  }
  void expect_op(const char* op, const Token* opener = nullptr) {
    if (accept_op(op)) {
      if (opener && !open_.empty() && open_.back() == opener) open_.pop_back();
      return;
    }
    if (opener && peek().kind == Tok::End)
      syntax_error(fmt::format("'{}' was never closed (column {})", opener->text, opener->column));
    unexpected();
  }
  [[noreturn]] void unexpected() const {
    const Token& t = peek();
    if (t.kind == Tok::End && !open_.empty())
      syntax_error(fmt::format("'{}' was never closed (column {})", open_.back()->text, open_.back()->column));
    switch (t.kind) {
      case Tok::End: syntax_error(fmt::format("invalid syntax: unexpected end of expression at column {}", t.column));
      case Tok::Op:
        if (t.text == ")" || t.text == "]" || t.text == "}")
          syntax_error(fmt::format("unmatched '{}' at column {}", t.text, t.column));
        syntax_error(fmt::format("invalid syntax: unexpected '{}' at column {}", t.text, t.column));
      case Tok::Name: syntax_error(fmt::format("invalid syntax: unexpected '{}' at column {}", t.text, t.column));
      default: syntax_error(fmt::format("invalid syntax: unexpected literal at column {}", t.column));
    }
  }

  class Deeper {
   public:
    explicit Deeper(Parser& p, bool enter = true) : p_(p) {
      if (enter) more();
    }
    ~Deeper() { p_.depth_ -= n_; }
    Deeper(const Deeper&) = delete;
    Deeper& operator=(const Deeper&) = delete;
    void more() {
      ++n_;
      if (++p_.depth_ > kMaxDepth || stack_nearly_full())
        throw EvalError("RecursionError",
                        fmt::format("the expression nests deeper than {} levels at column {} (parentheses, unary "
                                    "operators and each operator of a chain count): split it with xacro:property",
                                    kMaxDepth, p_.peek().column));
    }

   private:
    Parser& p_;
    int n_ = 0;
  };

  static std::shared_ptr<Node> node(Op op, int column) {
    auto n = std::make_shared<Node>();
    n->op = op;
    n->column = column;
    return n;
  }

  bool at_expression_end() const {
    const Token& t = peek();
    if (t.kind == Tok::End) return true;
    if (t.kind == Tok::Op) return t.text == ")" || t.text == "]" || t.text == "}" || t.text == ":" || t.text == "=";
    return is_kw("for") || is_kw("in");
  }

  // test (',' test)* [','] -- a tuple when there is a comma
  NodePtr testlist(bool allow_trailing_comma) {
    const int column = peek().column;
    NodePtr first = test();
    if (!is_op(",")) return first;
    auto tuple = node(Op::TupleLit, column);
    tuple->kids.push_back(first);
    while (accept_op(",")) {
      if (allow_trailing_comma && at_expression_end()) break;
      tuple->kids.push_back(test());
    }
    return tuple;
  }

  NodePtr test() {
    Deeper deeper(*this);
    if (is_kw("lambda")) return lambda();
    const int column = peek().column;
    NodePtr body = or_test();
    if (!is_kw("if")) return body;
    next();
    NodePtr cond = or_test();
    if (!accept_kw("else"))
      syntax_error(fmt::format("expected 'else' after 'if' expression (column {})", peek().column));
    auto n = node(Op::IfElse, column);
    n->kids = {body, cond, test()};
    return n;
  }

  NodePtr lambda() {
    auto n = node(Op::Lambda, next().column);
    while (!is_op(":")) {
      if (peek().kind != Tok::Name) unexpected();
      n->names.push_back(next().text);
      if (!accept_op(",")) break;
    }
    expect_op(":");
    n->kids.push_back(test());
    return n;
  }

  NodePtr or_test() {
    Deeper deeper(*this, false);
    NodePtr left = and_test();
    while (is_kw("or")) {
      deeper.more();
      auto n = node(Op::Or, next().column);
      n->kids = {left, and_test()};
      left = n;
    }
    return left;
  }

  NodePtr and_test() {
    Deeper deeper(*this, false);
    NodePtr left = not_test();
    while (is_kw("and")) {
      deeper.more();
      auto n = node(Op::And, next().column);
      n->kids = {left, not_test()};
      left = n;
    }
    return left;
  }

  NodePtr not_test() {
    if (is_kw("not")) {
      Deeper deeper(*this);
      auto n = node(Op::Not, next().column);
      n->kids.push_back(not_test());
      return n;
    }
    return comparison();
  }

  bool comparison_op(Cmp& c) {
    const Token& t = peek();
    if (t.kind == Tok::Op) {
      static const std::pair<const char*, Cmp> ops[] = {{"<", Cmp::Lt},  {"<=", Cmp::Le}, {">", Cmp::Gt},
                                                        {">=", Cmp::Ge}, {"==", Cmp::Eq}, {"!=", Cmp::Ne}};
      for (const auto& [text, cmp] : ops)
        if (t.text == text) {
          next();
          c = cmp;
          return true;
        }
      return false;
    }
    if (is_kw("in")) {
      next();
      c = Cmp::In;
      return true;
    }
    if (is_kw("not") && is_kw("in", 1)) {
      next();
      next();
      c = Cmp::NotIn;
      return true;
    }
    if (is_kw("is")) {
      next();
      c = accept_kw("not") ? Cmp::IsNot : Cmp::Is;
      return true;
    }
    return false;
  }

  NodePtr comparison() {
    const int column = peek().column;
    NodePtr first = bit_or();
    Cmp c;
    if (!comparison_op(c)) return first;
    auto n = node(Op::Compare, column);
    n->kids.push_back(first);
    do {
      n->cmps.push_back(c);
      n->kids.push_back(bit_or());
    } while (comparison_op(c));
    return n;
  }

  template <class Next>
  NodePtr binary_level(Next next_level, std::initializer_list<std::pair<const char*, Op>> ops) {
    Deeper deeper(*this, false);
    NodePtr left = (this->*next_level)();
    while (true) {
      const Token& t = peek();
      if (t.kind != Tok::Op) return left;
      bool matched = false;
      for (const auto& [text, op] : ops) {
        if (t.text == text) {
          deeper.more();
          auto n = node(op, next().column);
          n->kids = {left, (this->*next_level)()};
          left = n;
          matched = true;
          break;
        }
      }
      if (!matched) return left;
    }
  }

  NodePtr bit_or() { return binary_level(&Parser::bit_xor, {{"|", Op::BitOr}}); }
  NodePtr bit_xor() { return binary_level(&Parser::bit_and, {{"^", Op::BitXor}}); }
  NodePtr bit_and() { return binary_level(&Parser::shift, {{"&", Op::BitAnd}}); }
  NodePtr shift() { return binary_level(&Parser::arith, {{"<<", Op::Shl}, {">>", Op::Shr}}); }
  NodePtr arith() { return binary_level(&Parser::term, {{"+", Op::Add}, {"-", Op::Sub}}); }
  NodePtr term() {
    return binary_level(&Parser::factor, {{"*", Op::Mul}, {"/", Op::Div}, {"//", Op::FloorDiv}, {"%", Op::Mod}});
  }

  NodePtr factor() {
    static const std::pair<const char*, Op> unary[] = {{"-", Op::Neg}, {"+", Op::Pos}, {"~", Op::Invert}};
    for (const auto& [text, op] : unary) {
      if (is_op(text)) {
        Deeper deeper(*this);
        auto n = node(op, next().column);
        n->kids.push_back(factor());
        return n;
      }
    }
    return power();
  }

  NodePtr power() {
    NodePtr base = primary();
    if (!is_op("**")) return base;
    Deeper deeper(*this);
    auto n = node(Op::Pow, next().column);
    n->kids = {base, factor()};
    return n;
  }

  NodePtr primary() {
    Deeper deeper(*this, false);
    NodePtr n = atom();
    while (true) {
      if (is_op(".") || is_op("(") || is_op("[")) deeper.more();
      if (is_op(".")) {
        next();
        if (peek().kind != Tok::Name) unexpected();
        auto a = node(Op::Attr, peek().column);
        a->name = next().text;
        a->kids.push_back(n);
        n = a;
      } else if (is_op("(")) {
        n = call(n, opening());
      } else if (is_op("[")) {
        n = subscript(n, opening());
      } else {
        return n;
      }
    }
  }

  NodePtr call(NodePtr callee, const Token& open) {
    auto n = node(Op::Call, open.column);
    n->kids.push_back(callee);
    std::vector<NodePtr> keywords;
    while (!is_op(")")) {
      if (peek().kind == Tok::End) expect_op(")", &open);
      if (peek().kind == Tok::Name && is_op("=", 1)) {
        n->names.push_back(next().text);
        next();
        keywords.push_back(test());
      } else {
        if (!keywords.empty())
          syntax_error(fmt::format("positional argument follows keyword argument (column {})", peek().column));
        NodePtr arg = test();
        if (is_kw("for")) arg = comprehension(arg, nullptr, "gen", open.column);
        n->kids.push_back(arg);
      }
      if (!accept_op(",")) break;
    }
    expect_op(")", &open);
    for (auto& k : keywords) n->kids.push_back(std::move(k));
    return n;
  }

  NodePtr slice_part() {
    if (is_op(":") || is_op("]") || is_op(",")) return nullptr;
    return test();
  }

  NodePtr subscript(NodePtr target, const Token& open) {
    const int column = open.column;
    std::vector<NodePtr> items;
    NodePtr result;
    bool had_comma = false;
    while (true) {
      NodePtr lower = slice_part();
      if (is_op(":")) {
        next();
        auto s = node(Op::Slice, column);
        s->kids = {target, lower, slice_part(), nullptr};
        if (accept_op(":")) s->kids[3] = slice_part();
        result = s;
        if (!items.empty() || is_op(","))
          syntax_error(fmt::format("multi-dimensional slices are not supported (column {})", column));
        break;
      }
      if (!lower) unexpected();
      items.push_back(lower);
      if (!accept_op(",")) break;
      had_comma = true;
      if (is_op("]")) break;
    }
    expect_op("]", &open);
    if (result) return result;
    auto n = node(Op::Index, column);
    n->kids.push_back(target);
    if (!had_comma) {
      n->kids.push_back(items[0]);
    } else {
      auto t = node(Op::TupleLit, column);
      t->kids = std::move(items);
      n->kids.push_back(t);
    }
    return n;
  }

  NodePtr comprehension(NodePtr element, NodePtr value, const char* kind, int column) {
    auto n = node(Op::Comprehension, column);
    n->name = kind;
    n->kids.push_back(element);
    if (value) n->kids.push_back(value);
    while (accept_kw("for")) {
      ForClause f;
      const bool paren = accept_op("(");
      while (true) {
        if (peek().kind != Tok::Name) unexpected();
        f.targets.push_back(next().text);
        if (!accept_op(",")) break;
        f.tuple_target = true;
        if (is_kw("in") || is_op(")")) break;
      }
      if (paren) {
        expect_op(")");
        f.tuple_target = true;
      }
      if (!accept_kw("in")) unexpected();
      f.iter = or_test();
      while (accept_kw("if")) f.conditions.push_back(or_test());
      n->fors.push_back(std::move(f));
    }
    return n;
  }

  NodePtr atom() {
    const Token& t = peek();
    switch (t.kind) {
      case Tok::Number: return make_const(next().value, t.column);
      case Tok::String:
      case Tok::FString: return strings();
      case Tok::Name: {
        const Token& name = next();
        if (name.text == "True") return make_const(Value::boolean(true), name.column);
        if (name.text == "False") return make_const(Value::boolean(false), name.column);
        if (name.text == "None") return make_const(Value::none(), name.column);
        static const char* const keywords[] = {"and", "or", "not", "in", "is", "if", "else", "for", "lambda",
                                               "import", "def", "class", "return", "yield", "while", "del",
                                               "pass", "with", "as", "from", "global", "raise", "try", "await"};
        for (const char* kw : keywords)
          if (name.text == kw) {
            --pos_;
            unexpected();
          }
        auto n = node(Op::Name, name.column);
        n->name = name.text;
        return n;
      }
      case Tok::Op: {
        if (t.text == "(") return parenthesized(opening());
        if (t.text == "[") return list_display(opening());
        if (t.text == "{") return dict_display(opening());
        unexpected();
      }
      case Tok::End: unexpected();
    }
    unexpected();
  }

  NodePtr parenthesized(const Token& open) {
    if (is_op(")")) {
      expect_op(")", &open);
      return node(Op::TupleLit, open.column);
    }
    NodePtr first = test();
    if (is_kw("for")) {
      NodePtr gen = comprehension(first, nullptr, "gen", open.column);
      expect_op(")", &open);
      return gen;
    }
    if (is_op(")")) {
      expect_op(")", &open);
      return first;
    }
    auto tuple = node(Op::TupleLit, open.column);
    tuple->kids.push_back(first);
    while (accept_op(",")) {
      if (is_op(")")) break;
      tuple->kids.push_back(test());
    }
    expect_op(")", &open);
    return tuple;
  }

  NodePtr list_display(const Token& open) {
    auto n = node(Op::ListLit, open.column);
    if (is_op("]")) {
      expect_op("]", &open);
      return n;
    }
    NodePtr first = test();
    if (is_kw("for")) {
      NodePtr comp = comprehension(first, nullptr, "list", open.column);
      expect_op("]", &open);
      return comp;
    }
    n->kids.push_back(first);
    while (accept_op(",")) {
      if (is_op("]")) break;
      n->kids.push_back(test());
    }
    expect_op("]", &open);
    return n;
  }

  NodePtr dict_display(const Token& open) {
    auto n = node(Op::DictLit, open.column);
    if (is_op("}")) {
      expect_op("}", &open);
      return n;
    }
    NodePtr key = test();
    if (!is_op(":")) syntax_error(fmt::format("set displays are not supported (column {})", open.column));
    next();
    NodePtr value = test();
    if (is_kw("for")) {
      NodePtr comp = comprehension(key, value, "dict", open.column);
      expect_op("}", &open);
      return comp;
    }
    n->kids = {key, value};
    while (accept_op(",")) {
      if (is_op("}")) break;
      n->kids.push_back(test());
      expect_op(":");
      n->kids.push_back(test());
    }
    expect_op("}", &open);
    return n;
  }

  // Adjacent literals concatenate; an f-string among them makes the whole an FString node.
  NodePtr strings() {
    const int column = peek().column;
    auto f = node(Op::FString, column);
    std::string pending;
    bool any_f = false;
    while (peek().kind == Tok::String || peek().kind == Tok::FString) {
      const Token& t = next();
      if (t.kind == Tok::String) {
        pending += t.value.as_str();
        continue;
      }
      any_f = true;
      fstring_parts(t, *f, pending);
    }
    if (!any_f) return make_const(Value::string(std::move(pending)), column);
    if (!pending.empty()) {
      f->kids.push_back(make_const(Value::string(std::move(pending)), column));
      f->names.emplace_back();
    }
    return f;
  }

  static void fstring_parts(const Token& t, Node& f, std::string& pending) {
    const std::string& s = t.text;
    for (size_t i = 0; i < s.size(); ++i) {
      const char c = s[i];
      if ((c == '{' || c == '}') && i + 1 < s.size() && s[i + 1] == c) {
        pending += c;
        ++i;
        continue;
      }
      if (c == '}') syntax_error(fmt::format("f-string: single '}}' is not allowed (column {})", t.column));
      if (c != '{') {
        pending += c;
        continue;
      }
      int depth = 0;
      size_t j = i + 1, colon = std::string::npos, bang = std::string::npos;
      char quote = 0;
      for (; j < s.size(); ++j) {
        const char d = s[j];
        if (quote) {
          if (d == quote) quote = 0;
        } else if (d == '\'' || d == '"') {
          quote = d;
        } else if (d == '(' || d == '[' || d == '{') {
          ++depth;
        } else if (d == ')' || d == ']' || (d == '}' && depth > 0)) {
          --depth;
        } else if (d == '}') {
          break;
        } else if (depth == 0 && d == ':' && colon == std::string::npos) {
          colon = j;
        } else if (depth == 0 && d == '!' && j + 1 < s.size() && s[j + 1] != '=' && colon == std::string::npos) {
          bang = j;
        }
      }
      if (j >= s.size()) syntax_error(fmt::format("f-string: expecting '}}' (column {})", t.column));
      const size_t expr_end = bang != std::string::npos ? bang : colon != std::string::npos ? colon : j;
      std::string spec;
      if (bang != std::string::npos) spec += s[bang + 1];
      spec += ':';
      if (colon != std::string::npos) spec += s.substr(colon + 1, j - colon - 1);
      if (!pending.empty()) {
        f.kids.push_back(make_const(Value::string(std::move(pending)), t.column));
        f.names.emplace_back();
        pending.clear();
      }
      f.kids.push_back(Parser(std::string_view(s).substr(i + 1, expr_end - i - 1)).run());
      f.names.push_back(std::move(spec));
      i = j;
    }
  }

  std::vector<Token> toks_;
  int depth_ = 0;
  size_t pos_ = 0;
  std::vector<const Token*> open_;
};

}  // namespace

NodePtr parse(std::string_view text) { return Parser(text).run(); }

}  // namespace lcm_control::xacro::ast
