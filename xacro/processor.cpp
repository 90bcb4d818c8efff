// The xacro processor: walks the document as the official xacro's eval_all does (in read order), expanding macros,
// properties, includes, conditionals, xacro:element/attribute, `${...}` and `$(...)`, and reports a problem with
// its file:line and the chain of macro calls and includes. The rules are those of xacro 2.0.10 (ros2 branch).
#include <fmt/format.h>
#include <glob.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "xacro/process_error.hpp"
#include "xacro/python/python_expr.hpp"
#include "xacro/python/python_literals.hpp"
#include "xacro/source_file.hpp"
#include "xacro/substitution_args.hpp"
#include "xacro/python/value.hpp"
#include "xacro/xacro.hpp"
#include "xacro/xml_dom.hpp"
#include "xacro/yaml_values.hpp"

namespace lcm_control::xacro {

namespace {

using dom::Node;
using dom::NodeType;

struct Macro {
  std::string name;
  Node* body = nullptr;  // the xacro:macro element, detached
  std::vector<std::string> params;
  struct Default {
    bool forward = false;              // p:=^ or p:=^|default
    std::optional<std::string> value;  // the default's text
  };
  std::unordered_map<std::string, Default> defaults;
};

class MacroTable {
 public:
  explicit MacroTable(MacroTable* parent = nullptr) : parent_(parent) {}
  Macro* find(const std::string& name) {
    for (MacroTable* t = this; t; t = t->parent_) {
      auto it = t->macros_.find(name);
      if (it != t->macros_.end()) return it->second.get();
    }
    return nullptr;
  }
  MacroTable* find_namespace(const std::string& name) {
    for (MacroTable* t = this; t; t = t->parent_) {
      auto it = t->namespaces_.find(name);
      if (it != t->namespaces_.end()) return it->second.get();
    }
    return nullptr;
  }
  Macro& local(const std::string& name) {
    auto& m = macros_[name];
    if (!m) m = std::make_shared<Macro>();
    return *m;
  }
  MacroTable* new_namespace(const std::string& name) {
    auto ns = std::make_shared<MacroTable>();
    namespaces_[name] = ns;
    return ns.get();
  }

 private:
  MacroTable* parent_;
  std::unordered_map<std::string, std::shared_ptr<Macro>> macros_;
  std::unordered_map<std::string, std::shared_ptr<MacroTable>> namespaces_;
};

// xacro's Table: one scope of properties (the file's, a macro call's, an include namespace's), looked up through
// its parents. A lazy property keeps its text until first use, and is then evaluated in its own scope.
class Table {
 public:
  struct Entry {
    enum Kind { Evaluated, Lazy, Block, Namespace } kind = Evaluated;
    Value value;
    std::string text;  // Lazy
    Node* block = nullptr;
    std::shared_ptr<Table> ns;
    bool resolving = false;
  };

  explicit Table(Table* parent_table = nullptr, bool namespace_table = false)
      : parent(parent_table), is_namespace(namespace_table) {}

  std::pair<Table*, Entry*> find(const std::string& name) {
    for (Table* t = this; t; t = t->parent) {
      auto it = t->entries.find(name);
      if (it != t->entries.end()) return {t, &it->second};
    }
    return {nullptr, nullptr};
  }
  Table& top() {
    Table* t = this;
    while (t->parent) t = t->parent;
    return *t;
  }

  Table* parent;
  bool is_namespace;
  std::unordered_map<std::string, Entry> entries;
  std::vector<std::string> resolving;  // names being evaluated, for the circular definition message
};

// The names xacro's globals hold besides properties (a property of that name draws a warning, as in xacro).
bool is_global_symbol(const std::string& name) {
  static const std::unordered_set<std::string> names = {
      "list", "dict", "map", "len", "str", "float", "int", "True", "False", "min", "max", "round", "sorted", "range",
      "python", "math", "xacro", "load_yaml", "abs_filename", "dotify", "acos", "acosh", "asin", "asinh", "atan",
      "atan2", "atanh", "cbrt", "ceil", "comb", "copysign", "cos", "cosh", "degrees", "dist", "e", "erf", "erfc",
      "exp", "exp2", "expm1", "fabs", "factorial", "floor", "fmod", "frexp", "fsum", "gamma", "gcd", "hypot", "inf",
      "isclose", "isfinite", "isinf", "isnan", "isqrt", "lcm", "ldexp", "lgamma", "log", "log10", "log1p", "log2",
      "modf", "nan", "nextafter", "perm", "pi", "pow", "prod", "radians", "remainder", "sin", "sinh", "sqrt", "tan",
      "tanh", "tau", "trunc", "ulp"};
  return names.count(name) > 0;
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

bool is_space_text(const std::string& s) {  // Python's str.isspace()
  if (s.empty()) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
  });
}

bool has_non_space(const std::string& s) { return !s.empty() && !is_space_text(s); }

// xacro's Table._eval_literal: a property's or argument's text that reads as a number or a bool becomes one;
// '...' loses its quotes.
Value eval_literal(Value v) {
  if (v.kind() != Value::Kind::Str) return v;
  const std::string& s = v.as_str();
  if (s.size() >= 2 && s.front() == '\'' && s.back() == '\'') return Value::string(s.substr(1, s.size() - 2));
  if (s.find('_') != std::string::npos) return v;
  if (auto i = python_int(s)) return Value::integer(*i);
  if (auto d = python_float(s)) return Value::floating(*d);
  if (s == "true" || s == "True") return Value::boolean(true);
  if (s == "false" || s == "False") return Value::boolean(false);
  return v;
}

bool is_identifier(const std::string& s) {
  static const std::unordered_set<std::string> keywords = {
      "False", "None", "True", "and", "as", "assert", "async", "await", "break", "class", "continue", "def", "del",
      "elif", "else", "except", "finally", "for", "from", "global", "if", "import", "in", "is", "lambda",
      "nonlocal", "not", "or", "pass", "raise", "return", "try", "while", "with", "yield"};
  if (s.empty() || keywords.count(s)) return false;
  for (size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (!(std::isalpha(c) || c == '_' || c >= 0x80 || (i > 0 && std::isdigit(c)))) return false;
  }
  return true;
}

std::string join_path(const std::string& dir, const std::string& rel) {
  if (!rel.empty() && rel[0] == '/') return rel;
  if (dir.empty()) return rel;
  return dir.back() == '/' ? dir + rel : dir + "/" + rel;
}

std::string dirname(const std::string& path) {  // Python's os.path.dirname
  const size_t slash = path.rfind('/');
  if (slash == std::string::npos) return "";
  std::string head = path.substr(0, slash + 1);
  if (head.find_first_not_of('/') != std::string::npos)
    while (!head.empty() && head.back() == '/') head.pop_back();
  return head;
}

std::string canonical_key(const std::string& path) {
  std::error_code ec;
  auto p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  return ec ? path : p.string();
}

class Processor {
 public:
  explicit Processor(const Options& options) : options_(options) {
    for (const auto& [name, value] : options.args)
      if (!name.empty() && !value.empty()) args_[name] = value;
    marker_ = arena_.make(NodeType::Text);
    marker_->data = "\n\n";
    build_xacro_namespace();
  }

  Expansion run(const std::string& path) {
    filestack_.push_back(path);
    files_read_.push_back(path);
    const std::string* file = arena_.intern_file(path);
    Node* doc = nullptr;
    try {
      const std::string text = read_source_file(path);
      count_document_bytes(text.size());
      doc = dom::parse(text, file, arena_);
    } catch (const dom::ParseError& e) {
      throw XacroError(fmt::format("{}:{}: XML parsing error: {}", path, e.line(), e.what()));
    } catch (const ProcessError& e) {
      throw XacroError(e.what());
    }
    Node* root = doc->first_element();
    MacroTable macros;
    Table symbols;
    if (dom::Attr* target = root->attr("xacro:targetNamespace")) {
      std::string ns = target->value;
      root->remove_attr("xacro:targetNamespace");
      root->set_attr("xmlns", ns);
    }
    guarded(root, [&] { eval_all(root, macros, symbols); });

    const std::string rule(83, '=');
    const std::string banner[] = {
        fmt::format(" {} ", rule),
        fmt::format(" |    This document was autogenerated by xacro from {:<30} | ", path),
        fmt::format(" |    EDITING THIS FILE BY HAND IS NOT RECOMMENDED  {:<30} | ", ""),
        fmt::format(" {} ", rule),
    };
    Node* first = doc->first;
    for (const std::string& line : banner) {
      Node* c = arena_.make(NodeType::Comment);
      c->data = line;
      dom::insert_before(doc, c, first);
    }
    Expansion out;
    out.xml = dom::to_pretty_xml(doc);
    std::unordered_set<std::string> seen;
    for (const std::string& f : files_read_)
      if (seen.insert(f).second) out.files_read.push_back(f);
    return out;
  }

 private:
  struct Frame {
    bool macro;  // else an include
    std::string name;  // the macro, or the included file
    const std::string* def_file = nullptr;
    int def_line = 0;
    const std::string* site_file = nullptr;
    int site_line = 0;
  };

  // ---- messages ---------------------------------------------------------------------------------------------

  static std::string where(const Node* n) {
    if (!n || !n->file) return "<string>";
    int line = n->line;
    if (n->is_text()) {  // the line of the first substitution in the text, not where the text starts
      const size_t dollar = n->data.find('$');
      const std::string& d = n->data;
      line += static_cast<int>(std::count(d.begin(), d.begin() + (dollar == std::string::npos ? 0 : dollar), '\n'));
    }
    return fmt::format("{}:{}", *n->file, line);
  }

  std::string chain() const {
    std::string out;
    for (auto it = frames_.rbegin(); it != frames_.rend(); ++it) {
      if (it->macro)
        out += fmt::format("\n  when instantiating macro '{}' ({}:{}) at {}:{}", it->name, *it->def_file, it->def_line,
                           *it->site_file, it->site_line);
      else
        out += fmt::format("\n  in file included from {}:{}", *it->site_file, it->site_line);
    }
    return out;
  }

  // Runs f() for node n; a problem that is not yet located is reported at n, with the current chain.
  template <class F>
  void guarded(const Node* n, F&& f) {
    try {
      f();
    } catch (const XacroError&) {
      throw;
    } catch (const dom::ParseError& e) {
      throw XacroError(fmt::format("{}: {}{}", where(n), e.what(), chain()));
    } catch (const EvalError& e) {
      throw XacroError(fmt::format("{}: {}{}", where(n), e.what(), chain()));
    } catch (const std::exception& e) {
      throw XacroError(fmt::format("{}: {}{}", where(n), e.what(), chain()));
    }
  }

  void emit(const std::string& line) const {
    if (options_.message)
      options_.message(line);
    else
      std::fprintf(stderr, "%s\n", line.c_str());
  }

  void warn(const std::string& text) const { emit(fmt::format("{}: warning: {}{}", where(current_), text, chain())); }

  // ---- attributes ------------------------------------------------------------------------------------------

  // xacro's check_attrs: required and optional attributes (nullopt when absent); a warning for any other.
  std::vector<std::optional<std::string>> check_attrs(const Node* n, std::initializer_list<const char*> required,
                                                      std::initializer_list<const char*> optional) {
    std::vector<std::optional<std::string>> out;
    for (const char* r : required) {
      const dom::Attr* a = n->attr(r);
      if (!a) throw ProcessError(fmt::format("{}: missing attribute '{}'", n->name, r));
      out.emplace_back(a->value);
    }
    for (const char* o : optional) {
      const dom::Attr* a = n->attr(o);
      out.emplace_back(a ? std::optional<std::string>(a->value) : std::nullopt);
    }
    std::vector<std::string> extra;
    for (const dom::Attr& a : n->attrs) {
      bool known = starts_with(a.name, "xmlns:");
      for (const char* r : required) known = known || a.name == r;
      for (const char* o : optional) known = known || a.name == o;
      if (!known) extra.push_back(a.name);
    }
    if (!extra.empty()) warn(fmt::format("{}: unknown attribute(s): {}", n->name, fmt::join(extra, ", ")));
    return out;
  }

  // ---- text evaluation -------------------------------------------------------------------------------------

  class ScopeNames : public Names {
   public:
    ScopeNames(Processor& p, Table& t) : p_(p), t_(t) {}
    std::optional<Value> lookup(const std::string& name) const override { return p_.lookup(t_, name); }

   private:
    Processor& p_;
    Table& t_;
  };

  std::optional<Value> lookup(Table& symbols, const std::string& name) {
    auto [owner, entry] = symbols.find(name);
    if (entry) {
      switch (entry->kind) {
        case Table::Entry::Evaluated: return entry->value;
        case Table::Entry::Lazy: return resolve(*owner, name, *entry);
        case Table::Entry::Namespace: return namespace_dict(*entry->ns);
        case Table::Entry::Block: return std::nullopt;
      }
    }
    if (name == "xacro") return xacro_;
    if (name == "load_yaml" || name == "abs_filename" || name == "dotify") {
      warn(fmt::format("Using {}() directly is deprecated. Use xacro.{}() instead.", name, name));
      return *xacro_.as_dict().find(Value::string(name));
    }
    return std::nullopt;
  }

  Value resolve(Table& owner, const std::string& name, Table::Entry& entry) {
    if (entry.resolving) {
      std::string path;
      for (const std::string& r : owner.resolving) path += r + " -> ";
      throw ProcessError(fmt::format(
          "circular variable definition: {}{}\nConsider disabling lazy evaluation via lazy_eval=\"false\"", path,
          name));
    }
    entry.resolving = true;
    owner.resolving.push_back(name);
    Value v = eval_literal(eval_text(entry.text, owner));
    owner.resolving.pop_back();
    entry.resolving = false;
    entry.kind = Table::Entry::Evaluated;
    entry.value = v;
    entry.text.clear();
    return v;
  }

  Value namespace_dict(Table& ns) {
    Dict d;
    d.attribute_access = true;
    std::vector<std::string> names;
    for (const auto& [name, entry] : ns.entries)
      if (entry.kind != Table::Entry::Block) names.push_back(name);
    std::sort(names.begin(), names.end());
    for (const std::string& name : names)
      if (auto v = lookup(ns, name)) d.set(Value::string(name), *v);
    return Value::dict(std::move(d));
  }

  Value eval_text(const std::string& text, Table& symbols) {
    if (text.find('$') == std::string::npos) return Value::string(text);
    std::vector<Value> results;
    const size_t n = text.size();
    size_t i = 0;
    while (i < n) {
      if (text[i] != '$') {
        size_t k = text.find('$', i);
        if (k == std::string::npos) k = n;
        results.push_back(Value::string(text.substr(i, k - i)));
        i = k;
        continue;
      }
      size_t j = i;
      while (j < n && text[j] == '$') ++j;
      if (j - i >= 2 && j < n && (text[j] == '{' || text[j] == '(')) {  // $${ escapes ${
        results.push_back(Value::string(text.substr(i + 1, j - i)));
        i = j + 1;
        continue;
      }
      if (i + 1 < n && text[i + 1] == '{') {
        const size_t close = text.find('}', i + 2);
        if (close != std::string::npos) {
          results.push_back(eval_expression(text.substr(i + 2, close - i - 2), symbols));
          i = close + 1;
          continue;
        }
      }
      if (i + 1 < n && text[i + 1] == '(') {
        const size_t close = text.find(')', i + 2);
        if (close != std::string::npos) {
          results.push_back(Value::string(eval_extension(text.substr(i + 2, close - i - 2), symbols)));
          i = close + 1;
          continue;
        }
      }
      if (i + 1 == n) {
        results.push_back(Value::string("$"));
        break;
      }
      size_t k = i + 1;
      while (k < n && text[k] != '{' && text[k] != '(' && text[k] != '$') ++k;
      if (k == i + 1) throw ProcessError("invalid expression: " + text.substr(i));
      results.push_back(Value::string(text.substr(i, k - i)));
      i = k;
    }
    if (results.size() == 1) return results[0];
    std::string joined;
    for (const Value& v : results) {
      const std::string piece = v.kind() == Value::Kind::Str ? v.as_str() : str(v);
      check_string(joined.size() + piece.size());
      joined += piece;
    }
    return Value::string(std::move(joined));
  }

  std::string eval_str(const std::string& text, Table& symbols) {
    if (text.find('$') == std::string::npos) return text;
    Value v = eval_text(text, symbols);
    std::string out = v.kind() == Value::Kind::Str ? v.as_str() : str(v);
    count_document_bytes(out.size());
    return out;
  }

  Value eval_expression(const std::string& expression, Table& symbols) {
    try {
      const std::string text = eval_str(expression, symbols);
      const size_t b = text.find_first_not_of(" \t\n\r\f\v");
      const size_t e = text.find_last_not_of(" \t\n\r\f\v");
      const std::string stripped = b == std::string::npos ? std::string() : text.substr(b, e - b + 1);
      return evaluate(stripped, ScopeNames(*this, symbols));
    } catch (const XacroError&) {
      throw;
    } catch (const EvalError& e) {
      throw ProcessError(fmt::format("{}\nwhen evaluating expression '{}'", e.what(), expression));
    } catch (const ProcessError& e) {
      throw ProcessError(fmt::format("{}\nwhen evaluating expression '{}'", e.what(), expression));
    }
  }

  std::string eval_extension(const std::string& inner, Table& symbols) {
    const std::string text = eval_str(inner, symbols);
    SubstitutionContext ctx;
    ctx.args = &args_;
    ctx.find_package = options_.find_package;
    ctx.package_search_note = options_.package_search_note;
    ctx.current_file = filestack_.empty() ? std::string() : filestack_.back();
    ctx.anon = &anon_;
    return resolve_substitution(text, ctx);
  }

  // xacro's get_boolean_value: true/True/false/False or an integer for a text, Python's truth for other values.
  bool boolean_value(const Value& v, const std::optional<std::string>& condition) {
    if (v.kind() == Value::Kind::Str) {
      const std::string& s = v.as_str();
      if (s == "true" || s == "True") return true;
      if (s == "false" || s == "False") return false;
      if (auto i = python_int(s)) return *i != 0;
      throw ProcessError(fmt::format("Xacro conditional \"{}\" evaluated to \"{}\", which is not a boolean expression.",
                                     condition ? *condition : "None", s));
    }
    return truthy(v);
  }

  // ---- symbols ---------------------------------------------------------------------------------------------

  void set_symbol(Table& t, const std::string& name, Value value, bool lazy) {
    if (is_global_symbol(name)) warn("redefining global symbol: " + name);
    value = eval_literal(std::move(value));
    Table::Entry& e = t.entries[name];
    e = Table::Entry();
    if (lazy && value.kind() == Value::Kind::Str) {
      e.kind = Table::Entry::Lazy;
      e.text = value.as_str();
    } else {
      e.kind = Table::Entry::Evaluated;
      e.value = std::move(value);
    }
  }

  void set_block(Table& t, const std::string& name, Node* block) {
    Table::Entry& e = t.entries[name];
    e = Table::Entry();
    e.kind = Table::Entry::Block;
    e.block = block;
  }

  bool contains(Table& t, const std::string& name) { return t.find(name).second || is_global_symbol(name); }

  // ---- tree edits ------------------------------------------------------------------------------------------

  // xacro's remove_previous_comments: the comments right before a xacro element (at most one line break between)
  // go with it; a marker text then stops a later element from taking comments further up.
  void remove_previous_comments(Node* node) {
    Node* next = node->next;
    Node* previous = node->prev;
    while (previous) {
      if (previous->is_text() && is_space_text(previous->data) &&
          std::count(previous->data.begin(), previous->data.end(), '\n') <= 1)
        previous = previous->prev;
      if (previous && previous->type == NodeType::Comment) {
        Node* comment = previous;
        previous = previous->prev;
        dom::remove_child(comment);
      } else {
        if (next && next != marker_) dom::insert_before(node->parent, marker_, next);
        return;
      }
    }
  }

  // xacro's replace_node: node's place taken by `by` (or by its children), node removed.
  static void replace_node(Node* node, const std::vector<Node*>& by, bool content_only) {
    Node* parent = node->parent;
    for (Node* doc : by) {
      if (content_only) {
        Node* c = doc->first;
        while (c) {
          Node* n = c->next;
          dom::insert_before(parent, c, node);
          c = n;
        }
      } else {
        dom::insert_before(parent, doc, node);
      }
    }
    dom::remove_child(node);
  }

  void import_xml_namespaces(Node* parent, const Node* from) {
    for (const dom::Attr& a : from->attrs) {
      if (!starts_with(a.name, "xmlns:")) continue;
      const dom::Attr* old = parent->attr(a.name);
      if (old && old->value != a.value)
        warn(fmt::format("inconsistent namespace redefinitions for {}:\n old: {}\n new: {} ({})", a.name, old->value,
                         a.value, filestack_.back()));
      else
        parent->set_attr(a.name, a.value);
    }
  }

  // ---- the walk --------------------------------------------------------------------------------------------

  void eval_all(Node* node, MacroTable& macros, Table& symbols) {
    for (size_t i = 0; i < node->attrs.size();) {
      dom::Attr& a = node->attrs[i];
      if (starts_with(a.name, "xacro:")) {
        node->attrs.erase(node->attrs.begin() + static_cast<std::ptrdiff_t>(i));
        continue;
      }
      if (a.value.find('$') != std::string::npos) {
        std::string v = eval_str(a.value, symbols);
        node->attrs[i].value = std::move(v);
      }
      ++i;
    }
    node->remove_attr("xmlns:xacro");

    Node* child = node->first;
    bool eval_comments = false;
    while (child) {
      Node* next = child->next;
      current_ = child;
      bool again = false;
      guarded(child, [&] { again = eval_node(child, macros, symbols, eval_comments); });
      if (!again) child = next;
    }
  }

  // One child of eval_all's walk; true when the node is to be processed again (xacro:element renamed it).
  bool eval_node(Node* node, MacroTable& macros, Table& symbols, bool& eval_comments) {
    switch (node->type) {
      case NodeType::Text:
        if (node->data.find('$') != std::string::npos) node->data = eval_str(node->data, symbols);
        if (has_non_space(node->data)) eval_comments = false;
        return false;
      case NodeType::Comment:
        if (node->data.find("xacro:eval-comments") != std::string::npos) {
          eval_comments = node->data.find("xacro:eval-comments:off") == std::string::npos;
          dom::remove_child(node);
        } else if (eval_comments) {
          node->data = eval_str(node->data, symbols);
        }
        return false;
      case NodeType::CData:
      case NodeType::ProcessingInstruction: return false;
      case NodeType::Element: break;
    }
    eval_comments = false;
    const std::string& tag = node->name;
    if (!starts_with(tag, "xacro:")) {
      eval_all(node, macros, symbols);
      return false;
    }
    if (tag == "xacro:insert_block") {
      insert_block(node, macros, symbols);
    } else if (tag == "xacro:include") {
      process_include(node, macros, symbols);
    } else if (tag == "xacro:property") {
      grab_property(node, symbols);
    } else if (tag == "xacro:macro") {
      grab_macro(node, macros);
    } else if (tag == "xacro:arg") {
      auto attrs = check_attrs(node, {"name", "default"}, {});
      if (!args_.count(*attrs[0])) args_[*attrs[0]] = eval_str(*attrs[1], symbols);
      remove_previous_comments(node);
      dom::remove_child(node);
    } else if (tag == "xacro:element") {
      const dom::Attr* a = node->attr("xacro:name");
      if (!a) throw ProcessError(fmt::format("{}: missing attribute 'xacro:name'", tag));
      Value name = eval_text(a->value, symbols);
      if (!truthy(name)) throw ProcessError("xacro:element: empty name");
      node->remove_attr("xacro:name");
      node->name = str(name);
      return true;
    } else if (tag == "xacro:attribute") {
      const dom::Attr* n = node->attr("name");
      const dom::Attr* v = node->attr("value");
      if (!n) throw ProcessError(fmt::format("{}: missing attribute 'name'", tag));
      if (!v) throw ProcessError(fmt::format("{}: missing attribute 'value'", tag));
      const std::string name = eval_str(n->value, symbols);
      const std::string value = eval_str(v->value, symbols);
      if (name.empty()) throw ProcessError("xacro:attribute: empty name");
      node->parent->set_attr(name, value);
      dom::remove_child(node);
    } else if (tag == "xacro:if" || tag == "xacro:unless") {
      remove_previous_comments(node);
      auto attrs = check_attrs(node, {"value"}, {});
      bool keep = boolean_value(eval_text(*attrs[0], symbols), attrs[0]);
      if (tag == "xacro:unless") keep = !keep;
      if (keep) {
        eval_all(node, macros, symbols);
        replace_node(node, {node}, true);
      } else {
        dom::remove_child(node);
      }
    } else {
      macro_call(node, macros, symbols);
    }
    return false;
  }

  void insert_block(Node* node, MacroTable& macros, Table& symbols) {
    const std::string name = *check_attrs(node, {"name"}, {})[0];
    Node* block = nullptr;
    bool content_only = false;
    if (auto [t, e] = symbols.find("**" + name); e && e->kind == Table::Entry::Block) {
      block = e->block;
      content_only = true;
    } else if (auto [t2, e2] = symbols.find("*" + name); e2 && e2->kind == Table::Entry::Block) {
      block = e2->block;
    } else {
      throw ProcessError(fmt::format("Undefined block \"{}\"", name));
    }
    block = arena_.clone(block);
    eval_all(block, macros, symbols);
    replace_node(node, {block}, content_only);
  }

  std::vector<std::string> include_files(const std::string& spec, Table& symbols) {
    std::string filename = eval_str(spec, symbols);
    filename = join_path(dirname(filestack_.back()), filename);
    std::vector<std::string> files;
    if (filename.find_first_of("*[?") != std::string::npos) {
      glob_t g{};
      if (glob(filename.c_str(), GLOB_NOSORT, nullptr, &g) == 0)
        for (size_t i = 0; i < g.gl_pathc; ++i) files.emplace_back(g.gl_pathv[i]);
      globfree(&g);
      std::sort(files.begin(), files.end());
      if (files.empty()) warn(fmt::format("Include tag's filename spec \"{}\" matched no files.", filename));
    } else {
      files.push_back(filename);
    }
    for (const std::string& f : files) files_read_.push_back(f);
    return files;
  }

  void process_include(Node* elt, MacroTable& macros, Table& symbols) {
    auto attrs = check_attrs(elt, {"filename"}, {"ns", "optional"});
    MacroTable* ns_macros = &macros;
    Table* ns_symbols = &symbols;
    if (attrs[1] && !attrs[1]->empty()) {
      const std::string ns = eval_str(*attrs[1], symbols);
      ns_macros = macros.new_namespace(ns);
      if (is_global_symbol(ns)) warn("redefining global symbol: " + ns);
      Table::Entry& e = symbols.entries[ns];
      e = Table::Entry();
      e.kind = Table::Entry::Namespace;
      e.ns = std::make_shared<Table>(&symbols, true);
      ns_symbols = e.ns.get();
    }
    const bool optional = attrs[2] ? boolean_value(Value::string(*attrs[2]), std::nullopt) : false;
    if (elt->first_element()) warn("Child elements of a <xacro:include> tag are ignored");

    std::vector<Node*> included;
    for (const std::string& filename : include_files(*attrs[0], symbols)) {
      const std::string key = canonical_key(filename);
      for (const std::string& open : filestack_)
        if (canonical_key(open) == key) {
          std::string cycle;
          for (const std::string& f : filestack_) cycle += f + " -> ";
          throw ProcessError(fmt::format("include cycle: {}{}", cycle, filename));
        }
      count_include();
      std::string text;
      try {
        text = read_source_file(filename);
      } catch (const FileNotFound&) {
        if (optional) continue;
        throw;
      }
      const std::string* file = arena_.intern_file(filename);
      filestack_.push_back(filename);
      frames_.push_back(Frame{false, filename, nullptr, 0, elt->file, elt->line});
      Node* doc = nullptr;
      try {
        count_document_bytes(text.size());
        doc = dom::parse(text, file, arena_);
      } catch (const dom::ParseError& e) {
        throw XacroError(fmt::format("{}:{}: XML parsing error: {}{}", filename, e.line(), e.what(), chain()));
      }
      Node* root = doc->first_element();
      guarded(root, [&] { eval_all(root, *ns_macros, *ns_symbols); });
      frames_.pop_back();
      filestack_.pop_back();
      included.push_back(root);
      import_xml_namespaces(elt->parent, root);
    }
    remove_previous_comments(elt);
    replace_node(elt, included, true);
  }

  void grab_property(Node* elt, Table& table) {
    remove_previous_comments(elt);
    auto attrs = check_attrs(elt, {"name"}, {"value", "default", "remove", "scope", "lazy_eval"});
    std::string name = eval_str(*attrs[0], table);
    const auto& value_attr = attrs[1];
    const auto& default_attr = attrs[2];
    const auto& remove_attr = attrs[3];
    const auto& scope = attrs[4];
    const auto& lazy_attr = attrs[5];
    if (!is_identifier(name)) throw ProcessError("Property names must be valid python identifiers: " + name);
    if (starts_with(name, "__")) throw ProcessError("Property names must not start with double underscore:" + name);
    const bool remove = boolean_value(eval_text(remove_attr.value_or("false"), table), remove_attr);
    if ((value_attr ? 1 : 0) + (default_attr ? 1 : 0) + (remove ? 1 : 0) > 1)
      throw ProcessError("Property attributes default, value, and remove are mutually exclusive: " + name);
    if (remove && contains(table, name)) {
      for (Table* t = &table; t; t = t->parent) t->entries.erase(name);
      if (is_global_symbol(name)) warn("Cannot remove global symbol: " + name);
      dom::remove_child(elt);
      return;
    }
    std::optional<std::string> value = value_attr;
    if (default_attr) {
      if (scope) warn(name + ": default property value can only be defined on local scope");
      if (!contains(table, name)) {
        value = default_attr;
      } else {
        dom::remove_child(elt);
        return;
      }
    }
    dom::remove_child(elt);

    bool lazy = boolean_value(eval_text(lazy_attr.value_or("true"), table), lazy_attr);
    Table* target = &table;
    if (scope && *scope == "global") {
      target = &table.top();
      lazy = false;
    } else if (scope && *scope == "parent") {
      if (!table.parent) {
        warn(name + ": no parent scope at global scope ");
        return;
      }
      target = table.parent;
      lazy = false;
      if (!table.is_namespace)
        while (target->is_namespace) target = target->parent;
    }
    if (!value) {
      set_block(*target, "**" + name, elt);
      return;
    }
    if (!lazy) {
      set_symbol(*target, name, eval_text(*value, table), false);
    } else {
      set_symbol(*target, name, Value::string(*value), true);
    }
  }

  void grab_macro(Node* elt, MacroTable& macros) {
    remove_previous_comments(elt);
    auto attrs = check_attrs(elt, {"name"}, {"params"});
    std::string name = *attrs[0];
    if (name == "call") throw ProcessError("Invalid use of macro name 'call'");
    if (name.find('.') != std::string::npos)
      throw ProcessError("macro names must not contain '.' (reserved for namespaces): " + name);
    if (starts_with(name, "xacro:")) {
      warn("macro names must not contain prefix 'xacro:': " + name);
      name = name.substr(6);
    }
    Macro& m = macros.local(name);
    m.name = name;
    m.body = elt;
    m.params.clear();
    m.defaults.clear();
    std::string params = attrs[1].value_or("");
    static const std::regex param_re(
        "^\\s*([^\\s:=]+?)\\s*:?=\\s*(\\^\\|?)?(\\$\\{.*?\\}|\\$\\(.*?\\)|(?:'.*?'|\".*?\"|[^\\s'\"]+)+|)(?:\\s+|$)(.*)");
    while (!params.empty()) {
      std::smatch match;
      if (std::regex_search(params, match, param_re)) {
        const std::string param = match[1];
        Macro::Default d;
        d.forward = match[2].matched;
        if (match[3].length() > 0) d.value = match[3].str();
        m.params.push_back(param);
        m.defaults[param] = d;
        params = match[4];
      } else {
        const size_t b = params.find_first_not_of(" \t\n\r\f\v");
        if (b == std::string::npos) break;
        const size_t e = params.find_first_of(" \t\n\r\f\v", b);
        m.params.push_back(params.substr(b, e == std::string::npos ? std::string::npos : e - b));
        const size_t rest = e == std::string::npos ? std::string::npos : params.find_first_not_of(" \t\n\r\f\v", e);
        params = rest == std::string::npos ? std::string() : params.substr(rest);
      }
    }
    dom::remove_child(elt);
  }

  void macro_call(Node* node, MacroTable& macros_in, Table& symbols_in) {
    if (node->name == "xacro:call") {
      const dom::Attr* a = node->attr("macro");
      if (!a) throw ProcessError("xacro:call: missing attribute 'macro'");
      if (a->value.empty()) throw ProcessError("xacro:call is missing the 'macro' attribute");
      const std::string name = eval_str(a->value, symbols_in);
      node->remove_attr("macro");
      node->name = "xacro:" + name;
    }
    const std::string fullname = node->name.substr(6);
    MacroTable* macros = &macros_in;
    Table* symbols = &symbols_in;
    Macro* m = macros->find(fullname);
    if (!m) {
      const size_t dot = fullname.rfind('.');
      if (dot != std::string::npos) {
        size_t start = 0;
        while (macros && symbols && start < dot) {
          size_t end = fullname.find('.', start);
          const std::string ns = fullname.substr(start, end - start);
          macros = macros->find_namespace(ns);
          auto [owner, entry] = symbols->find(ns);
          symbols = entry && entry->kind == Table::Entry::Namespace ? entry->ns.get() : nullptr;
          start = end + 1;
        }
        if (macros && symbols) m = macros->find(fullname.substr(dot + 1));
      }
    }
    if (!m)
      throw ProcessError(fmt::format("unknown macro name: {} (no <xacro:macro name=\"{}\"> is defined before this "
                                     "point, in this scope, or in an included file)",
                                     node->name, fullname));
    if (frames_.size() > 400) throw ProcessError("maximum recursion depth exceeded when instantiating macro " + m->name);
    count_macro_call();
    frames_.push_back(Frame{true, m->name, m->body->file, m->body->line, node->file, node->line});

    Node* body = arena_.clone(m->body);
    Table scoped_symbols(symbols);
    MacroTable scoped_macros(macros);
    std::vector<std::string> params = m->params;
    for (dom::Attr& a : node->attrs) {
      auto it = std::find(params.begin(), params.end(), a.name);
      if (it == params.end()) throw ProcessError(fmt::format("Invalid parameter \"{}\" of macro '{}'", a.name, m->name));
      params.erase(it);
      set_symbol(scoped_symbols, a.name, eval_text(a.value, *symbols), false);
      a.value.clear();
    }
    eval_all(node, *macros, *symbols);

    Node* block = node->first_element();
    for (auto it = params.begin(); it != params.end();) {
      if ((*it)[0] != '*') {
        ++it;
        continue;
      }
      if (!block) throw ProcessError(fmt::format("Not enough blocks for macro '{}'", m->name));
      set_block(scoped_symbols, *it, block);
      block = block->next_element();
      it = params.erase(it);
    }
    if (block) throw ProcessError(fmt::format("Unused block \"{}\" in the call of macro '{}'", block->name, m->name));

    for (auto it = params.begin(); it != params.end();) {
      auto d = m->defaults.find(*it);
      if (d == m->defaults.end() || (!d->second.forward && !d->second.value)) {
        ++it;
        continue;
      }
      Value v;
      if (d->second.forward) {
        auto [owner, entry] = symbols->find(*it);
        if (entry && entry->kind != Table::Entry::Block && entry->kind != Table::Entry::Namespace) {
          v = *lookup(*symbols, *it);
        } else if (d->second.value) {
          v = eval_text(*d->second.value, *symbols);
        } else {
          throw ProcessError(fmt::format("Undefined property to forward: {} (macro '{}' takes it with {}:=^ from the "
                                         "scope of its call)",
                                         *it, m->name, *it));
        }
      } else {
        v = eval_text(*d->second.value, *symbols);
      }
      set_symbol(scoped_symbols, *it, std::move(v), false);
      it = params.erase(it);
    }
    if (!params.empty())
      throw ProcessError(fmt::format("Undefined parameters [{}] of macro '{}'", fmt::join(params, ","), m->name));

    eval_all(body, scoped_macros, scoped_symbols);
    remove_previous_comments(node);
    import_xml_namespaces(node->parent, body);
    replace_node(node, {body}, true);
    frames_.pop_back();
  }

  // ---- the xacro object ------------------------------------------------------------------------------------

  std::string location_lines() const { return where(current_) + chain(); }

  void build_xacro_namespace() {
    Dict d;
    d.attribute_access = true;
    auto add = [&d](const std::string& name, std::function<Value(const List&, const Kwargs&)> fn) {
      d.set(Value::string(name), Value::callable("xacro." + name, std::move(fn)));
    };
    auto joined = [](const List& args) {
      std::string s;
      for (size_t i = 0; i < args.size(); ++i) s += (i ? " " : "") + str(args[i]);
      return s;
    };
    auto wants_location = [](const Kwargs& kwargs, bool dflt) {
      for (const auto& [k, v] : kwargs)
        if (k == "print_location") return truthy(v);
      return dflt;
    };
    add("load_yaml", [this](const List& args, const Kwargs&) {
      if (args.size() != 1) throw EvalError("TypeError", "load_yaml() takes exactly one argument (the file name)");
      const std::string filename = join_path(dirname(filestack_.back()), str(args[0]));
      files_read_.push_back(filename);
      auto cached = yaml_cache_.find(filename);  // values are immutable: a file read again is the same value
      if (cached != yaml_cache_.end()) return cached->second;
      Value v = load_yaml_file(filename);
      yaml_cache_.emplace(filename, v);
      return v;
    });
    add("abs_filename", [this](const List& args, const Kwargs&) {
      if (args.size() != 1) throw EvalError("TypeError", "abs_filename() takes exactly one argument");
      return Value::string(join_path(dirname(filestack_.back()), str(args[0])));
    });
    add("dotify", [](const List& args, const Kwargs&) {
      if (args.size() != 1) throw EvalError("TypeError", "dotify() takes exactly one argument (a dict)");
      Dict copy = args[0].as_dict();
      copy.attribute_access = true;
      return Value::dict(std::move(copy));
    });
    add("arg", [this](const List& args, const Kwargs&) {
      if (args.size() != 1) throw EvalError("TypeError", "arg() takes exactly one argument (the arg's name)");
      const std::string name = str(args[0]);
      auto it = args_.find(name);
      if (it == args_.end()) throw EvalError("KeyError", repr(args[0]));
      return Value::string(it->second);
    });
    add("message", [this, joined, wants_location](const List& args, const Kwargs& kwargs) {
      emit(joined(args));
      if (wants_location(kwargs, false)) emit(location_lines());
      return Value::string("");
    });
    add("warning", [this, joined, wants_location](const List& args, const Kwargs& kwargs) {
      emit("warning: " + joined(args));
      if (wants_location(kwargs, true)) emit(location_lines());
      return Value::string("");
    });
    add("error", [this, joined, wants_location](const List& args, const Kwargs& kwargs) {
      emit("error: " + joined(args));
      if (wants_location(kwargs, true)) emit(location_lines());
      return Value::string("");
    });
    add("print_location", [this](const List&, const Kwargs&) {
      emit(location_lines());
      return Value::string("");
    });
    add("fatal", [joined](const List& args, const Kwargs&) -> Value { throw ProcessError(joined(args)); });
    add("tokenize", [](const List& args, const Kwargs& kwargs) {
      if (args.empty()) throw EvalError("TypeError", "tokenize() missing the string");
      const std::string s = str(args[0]);
      std::string sep = args.size() > 1 ? str(args[1]) : ",; ";
      bool skip_empty = args.size() > 2 ? truthy(args[2]) : true;
      for (const auto& [k, v] : kwargs) {
        if (k == "sep") sep = str(v);
        if (k == "skip_empty") skip_empty = truthy(v);
      }
      List out;
      size_t i = 0;
      while (true) {
        const size_t j = s.find_first_of(sep, i);
        std::string token = s.substr(i, j == std::string::npos ? std::string::npos : j - i);
        if (!token.empty() || !skip_empty) out.push_back(Value::string(token));
        if (j == std::string::npos) break;
        i = j + 1;
      }
      return Value::list(std::move(out));
    });
    xacro_ = Value::dict(std::move(d));
  }

  const Options& options_;
  dom::Arena arena_;
  std::map<std::string, std::string> args_;
  std::map<std::string, std::string> anon_;
  std::vector<std::string> filestack_;
  std::vector<std::string> files_read_;
  std::vector<Frame> frames_;
  std::unordered_map<std::string, Value> yaml_cache_;
  Node* marker_ = nullptr;
  const Node* current_ = nullptr;
  Value xacro_;
};

}  // namespace

Expansion expand_file(const std::string& path, const Options& options) {
  const BudgetScope budget(options.budget);
  Processor processor(options);
  Expansion out = processor.run(path);
  out.budget_use = budget.use();
  return out;
}

std::pair<std::string, std::string> parse_arg(const std::string& text) {
  const size_t pos = text.find(":=");
  if (pos == std::string::npos || text.find(":=", pos + 2) != std::string::npos)
    throw std::invalid_argument("not a NAME:=VALUE argument: '" + text + "'");
  auto trim = [](std::string s) {
    const size_t b = s.find_first_not_of(" \t\n\r");
    const size_t e = s.find_last_not_of(" \t\n\r");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  std::string name = trim(text.substr(0, pos));
  if (name.empty()) throw std::invalid_argument("an argument without a name: '" + text + "'");
  return {name, trim(text.substr(pos + 2))};
}

bool is_xacro(const std::string& path) {
  const size_t slash = path.rfind('/');
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  return name.find(".xacro") != std::string::npos;
}

}  // namespace lcm_control::xacro
