// The minidom-like document tree: parsing a file as expat does, tree edits, and xacro's pretty printer.
#include "xacro/xml_dom.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "xacro/budget.hpp"
#include "xacro/python/utf8.hpp"

namespace lcm_control::xacro::dom {

const Attr* Node::attr(const std::string& n) const {
  for (const Attr& a : attrs)
    if (a.name == n) return &a;
  return nullptr;
}

Attr* Node::attr(const std::string& n) {
  for (Attr& a : attrs)
    if (a.name == n) return &a;
  return nullptr;
}

void Node::set_attr(const std::string& n, std::string v) {
  if (Attr* a = attr(n))
    a->value = std::move(v);
  else
    attrs.push_back({n, std::move(v)});
}

bool Node::remove_attr(const std::string& n) {
  for (auto it = attrs.begin(); it != attrs.end(); ++it)
    if (it->name == n) {
      attrs.erase(it);
      return true;
    }
  return false;
}

Node* Node::first_element() const {
  Node* c = first;
  while (c && !c->is_element()) c = c->next;
  return c;
}

Node* Node::next_element() const {
  Node* c = next;
  while (c && !c->is_element()) c = c->next;
  return c;
}

Node* Arena::make(NodeType type) {
  count_nodes(1);
  Node& n = nodes_.emplace_back();
  n.type = type;
  return &n;
}

Node* Arena::clone(const Node* src) {
  Node* n = make(src->type);
  n->name = src->name;
  n->data = src->data;
  n->attrs = src->attrs;
  size_t bytes = n->name.size() + n->data.size();
  for (const Attr& a : n->attrs) bytes += a.name.size() + a.value.size();
  count_document_bytes(bytes);
  n->file = src->file;
  n->line = src->line;
  for (const Node* c = src->first; c; c = c->next) append_child(n, clone(c));
  return n;
}

const std::string* Arena::intern_file(const std::string& path) { return &files_.emplace_back(path); }

void remove_child(Node* child) {
  Node* p = child->parent;
  if (!p) return;
  (child->prev ? child->prev->next : p->first) = child->next;
  (child->next ? child->next->prev : p->last) = child->prev;
  child->parent = child->prev = child->next = nullptr;
}

void insert_before(Node* parent, Node* n, Node* ref) {
  remove_child(n);
  n->parent = parent;
  if (!ref) {
    n->prev = parent->last;
    (parent->last ? parent->last->next : parent->first) = n;
    parent->last = n;
    return;
  }
  n->next = ref;
  n->prev = ref->prev;
  (ref->prev ? ref->prev->next : parent->first) = n;
  ref->prev = n;
}

void append_child(Node* parent, Node* n) { insert_before(parent, n, nullptr); }

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }


class Parser {
 public:
  Parser(const std::string& text, const std::string* file, Arena& arena) : s_(text), file_(file), arena_(arena) {}

  Node* run() {
    Node* doc = arena_.make(NodeType::Element);
    doc->file = file_;
    doc->line = 1;
    Node* root = nullptr;
    if (s_.compare(0, 3, "\xEF\xBB\xBF") == 0) i_ = 3;
    while (true) {
      skip_space();
      if (i_ >= s_.size()) break;
      if (starts("<?")) {
        Node* pi = processing_instruction();
        if (pi) append_child(doc, pi);
      } else if (starts("<!--")) {
        append_child(doc, comment());
      } else if (starts("<!DOCTYPE")) {
        doctype();
      } else if (s_[i_] == '<') {
        if (root) fail("junk after document element");
        root = element();
        append_child(doc, root);
      } else {
        fail(root ? "junk after document element" : "syntax error");
      }
    }
    if (!root) fail("no element found");
    return doc;
  }

 private:
  [[noreturn]] void fail(const std::string& what) { throw ParseError(what, line_); }

  bool starts(const char* p) const { return s_.compare(i_, std::strlen(p), p) == 0; }

  void advance(size_t n = 1) {
    for (size_t k = 0; k < n && i_ < s_.size(); ++k, ++i_)
      if (s_[i_] == '\n') ++line_;
  }

  void skip_space() {
    while (i_ < s_.size() && is_space(s_[i_])) advance();
  }

  // Up to `end`; returns the text between, line ends normalised.
  std::string until(const char* end, const char* what) {
    size_t j = s_.find(end, i_);
    if (j == std::string::npos) fail(std::string("unclosed ") + what);
    std::string out;
    out.reserve(j - i_);
    for (size_t k = i_; k < j; ++k) {
      if (s_[k] == '\r') {
        out += '\n';
        if (k + 1 < j && s_[k + 1] == '\n') ++k;
      } else {
        out += s_[k];
      }
    }
    advance(j - i_ + std::strlen(end));
    return out;
  }

  Node* processing_instruction() {
    const int line = line_;
    advance(2);
    size_t j = i_;
    while (j < s_.size() && !is_space(s_[j]) && s_[j] != '?') ++j;
    std::string target = s_.substr(i_, j - i_);
    advance(j - i_);
    skip_space();
    std::string data = until("?>", "processing instruction");
    if (target == "xml") return nullptr;  // the declaration
    Node* n = arena_.make(NodeType::ProcessingInstruction);
    n->name = target;
    n->data = data;
    n->file = file_;
    n->line = line;
    return n;
  }

  Node* comment() {
    const int line = line_;
    advance(4);
    std::string data = until("-->", "comment");
    Node* n = arena_.make(NodeType::Comment);
    n->data = std::move(data);
    n->file = file_;
    n->line = line;
    return n;
  }

  void doctype() {
    int depth = 0;
    while (i_ < s_.size()) {
      char c = s_[i_];
      advance();
      if (c == '[') ++depth;
      if (c == ']') --depth;
      if (c == '>' && depth <= 0) return;
    }
    fail("unclosed DOCTYPE");
  }

  void entity(std::string& out) {
    size_t semi = s_.find(';', i_);
    if (semi == std::string::npos || semi - i_ > 12) fail("not well-formed (invalid token)");
    std::string name = s_.substr(i_ + 1, semi - i_ - 1);
    if (name == "lt") out += '<';
    else if (name == "gt") out += '>';
    else if (name == "amp") out += '&';
    else if (name == "quot") out += '"';
    else if (name == "apos") out += '\'';
    else if (name.size() > 1 && name[0] == '#') {
      unsigned long cp = 0;
      try {
        cp = name[1] == 'x' ? std::stoul(name.substr(2), nullptr, 16) : std::stoul(name.substr(1), nullptr, 10);
      } catch (const std::exception&) {
        fail("not well-formed (invalid token)");
      }
      if (cp == 0 || cp > 0x10FFFF) fail("reference to invalid character number");
      append_utf8(out, cp);
    } else {
      fail("undefined entity &" + name + ";");
    }
    advance(semi - i_ + 1);
  }

  std::string name_token() {
    size_t j = i_;
    while (j < s_.size() && !is_space(s_[j]) && !std::strchr("/>=<\"'", s_[j])) ++j;
    if (j == i_) fail("not well-formed (invalid token)");
    std::string n = s_.substr(i_, j - i_);
    advance(j - i_);
    return n;
  }

  // Elements nest at most this deep (a URDF nests a handful): every walk of the tree recurses per level.
  static constexpr int kMaxDepth = 1000;

  Node* element() {
    if (++depth_ > kMaxDepth || stack_nearly_full())
      fail(fmt::format("elements nest deeper than {} levels: every walk of the document recurses per level", kMaxDepth));
    struct Leave {
      int& d;
      ~Leave() { --d; }
    } leave{depth_};
    Node* e = arena_.make(NodeType::Element);
    e->file = file_;
    e->line = line_;
    advance(1);  // <
    e->name = name_token();
    while (true) {
      skip_space();
      if (i_ >= s_.size()) fail("unclosed token");
      if (starts("/>")) {
        advance(2);
        return e;
      }
      if (s_[i_] == '>') {
        advance();
        break;
      }
      std::string an = name_token();
      skip_space();
      if (i_ >= s_.size() || s_[i_] != '=') fail("not well-formed (invalid token)");
      advance();
      skip_space();
      if (i_ >= s_.size() || (s_[i_] != '"' && s_[i_] != '\'')) fail("not well-formed (invalid token)");
      const char q = s_[i_];
      advance();
      std::string v;
      while (true) {
        if (i_ >= s_.size()) fail("unclosed token");
        char c = s_[i_];
        if (c == q) {
          advance();
          break;
        }
        if (c == '<') fail("not well-formed (invalid token)");
        if (c == '&') {
          entity(v);
          continue;
        }
        if (c == '\r') {
          v += ' ';
          advance();
          if (i_ < s_.size() && s_[i_] == '\n') advance();
          continue;
        }
        v += (c == '\n' || c == '\t') ? ' ' : c;
        advance();
      }
      if (e->attr(an)) fail("duplicate attribute");
      e->attrs.push_back({std::move(an), std::move(v)});
    }
    // content
    while (true) {
      if (i_ >= s_.size()) fail("no element found");
      if (starts("</")) {
        advance(2);
        std::string closing = name_token();
        if (closing != e->name) fail("mismatched tag");
        skip_space();
        if (i_ >= s_.size() || s_[i_] != '>') fail("not well-formed (invalid token)");
        advance();
        return e;
      }
      if (starts("<!--")) {
        append_child(e, comment());
      } else if (starts("<![CDATA[")) {
        const int line = line_;
        advance(9);
        Node* c = arena_.make(NodeType::CData);
        c->data = until("]]>", "CDATA section");
        c->file = file_;
        c->line = line;
        append_child(e, c);
      } else if (starts("<?")) {
        if (Node* pi = processing_instruction()) append_child(e, pi);
      } else if (s_[i_] == '<') {
        append_child(e, element());
      } else {
        text(e);
      }
    }
  }

  void text(Node* parent) {
    Node* t;
    if (parent->last && parent->last->is_text()) {
      t = parent->last;  // expat's pieces of one text (around a comment-free entity) are one node
    } else {
      t = arena_.make(NodeType::Text);
      t->file = file_;
      t->line = line_;
      append_child(parent, t);
    }
    while (i_ < s_.size() && s_[i_] != '<') {
      char c = s_[i_];
      if (c == '&') {
        entity(t->data);
        continue;
      }
      if (c == '\r') {
        t->data += '\n';
        advance();
        if (i_ < s_.size() && s_[i_] == '\n') advance();
        continue;
      }
      t->data += c;
      advance();
    }
  }

  const std::string& s_;
  const std::string* file_;
  Arena& arena_;
  size_t i_ = 0;
  int line_ = 1;
  int depth_ = 0;
};

// minidom's _write_data (Python 3.8-3.12, which the official xacro's writer needs).
void write_data(std::string& out, const std::string& data) {
  for (char c : data) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '"': out += "&quot;"; break;
      case '>': out += "&gt;"; break;
      default: out += c;
    }
  }
}

bool is_blank(const std::string& s) {
  // Python's str.isspace() is False for ""; the writer skips "" and whitespace alike.
  return std::all_of(s.begin(), s.end(), [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' ||
                                                            c == '\f' || c == '\v'; });
}

void write_node(std::string& out, const Node* n, const std::string& indent);

void write_element(std::string& out, const Node* e, const std::string& indent) {
  out += indent;
  out += '<';
  out += e->name;
  std::vector<const Attr*> sorted;
  sorted.reserve(e->attrs.size());
  for (const Attr& a : e->attrs) sorted.push_back(&a);
  std::sort(sorted.begin(), sorted.end(), [](const Attr* a, const Attr* b) { return a->name < b->name; });
  for (const Attr* a : sorted) {
    out += ' ';
    out += a->name;
    out += "=\"";
    write_data(out, a->value);
    out += '"';
  }
  if (!e->first) {
    out += "/>\n";
    return;
  }
  if (e->first == e->last && e->first->is_text()) {
    out += '>';
    write_data(out, e->first->data);
    out += "</";
    out += e->name;
    out += ">\n";
    return;
  }
  out += ">\n";
  const std::string inner = indent + "  ";
  for (const Node* c = e->first; c; c = c->next) {
    if (c->is_text() && is_blank(c->data)) continue;
    write_node(out, c, inner);
    check_document(out.size());
  }
  out += indent;
  out += "</";
  out += e->name;
  out += ">\n";
}

void write_node(std::string& out, const Node* n, const std::string& indent) {
  switch (n->type) {
    case NodeType::Element: write_element(out, n, indent); break;
    case NodeType::Text:
      write_data(out, indent);
      write_data(out, n->data);
      out += '\n';
      break;
    case NodeType::Comment:
      out += indent;
      out += "<!--";
      out += n->data;
      out += "-->\n";
      break;
    case NodeType::CData:
      out += "<![CDATA[";
      out += n->data;
      out += "]]>";
      break;
    case NodeType::ProcessingInstruction:
      out += indent;
      out += "<?";
      out += n->name;
      out += ' ';
      out += n->data;
      out += "?>\n";
      break;
  }
}

}  // namespace

Node* parse(const std::string& text, const std::string* file, Arena& arena) {
  return Parser(text, file, arena).run();
}

std::string to_pretty_xml(const Node* document) {
  std::string out = "<?xml version=\"1.0\" ?>\n";
  for (const Node* c = document->first; c; c = c->next) write_node(out, c, "");
  return out;
}

}  // namespace lcm_control::xacro::dom
