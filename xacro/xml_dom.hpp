// The document tree xacro works on, shaped like Python's xml.dom.minidom (what the official xacro edits in place):
// linked nodes that can be moved, cloned and removed while a walk is under way; a parser that reads a file as expat
// does (entities decoded, attribute whitespace normalised, line numbers kept); and the writer of minidom's
// toprettyxml(indent="  ") as xacro patches it (attributes sorted, whitespace-only text skipped).
#pragma once

#include <deque>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace lcm_control::xacro::dom {

enum class NodeType { Element, Text, Comment, CData, ProcessingInstruction };

struct Attr {
  std::string name, value;
};

struct Node {
  NodeType type = NodeType::Element;
  std::string name;  // element: the tag (with its prefix: "xacro:macro"); processing instruction: the target
  std::string data;  // text, comment, CDATA, processing instruction data
  std::vector<Attr> attrs;  // in document order
  Node* parent = nullptr;
  Node* first = nullptr;
  Node* last = nullptr;
  Node* prev = nullptr;
  Node* next = nullptr;
  const std::string* file = nullptr;  // the source file (owned by the Arena), for messages
  int line = 0;

  bool is_element() const { return type == NodeType::Element; }
  bool is_text() const { return type == NodeType::Text; }
  const Attr* attr(const std::string& n) const;
  Attr* attr(const std::string& n);
  void set_attr(const std::string& n, std::string v);  // replaces in place, else appends
  bool remove_attr(const std::string& n);
  Node* first_element() const;
  Node* next_element() const;
};

// Owns every node of one expansion (parsed files, clones); nodes are freed with the arena.
class Arena {
 public:
  Node* make(NodeType type);
  Node* clone(const Node* n);  // deep copy, detached
  const std::string* intern_file(const std::string& path);

 private:
  std::deque<Node> nodes_;
  std::deque<std::string> files_;
};

// Tree edits with minidom's meaning.
void remove_child(Node* child);                        // detaches it from its parent
void insert_before(Node* parent, Node* n, Node* ref);  // ref == nullptr appends; n is detached first
void append_child(Node* parent, Node* n);

class ParseError : public std::runtime_error {
 public:
  ParseError(const std::string& what, int line) : std::runtime_error(what), line_(line) {}
  int line() const { return line_; }

 private:
  int line_;
};

// A parsed file: a document node (type Element, empty name) whose children are the top-level comments, processing
// instructions and the one root element. Throws ParseError ("not well-formed (invalid token)", line).
Node* parse(const std::string& text, const std::string* file, Arena& arena);

// The document as xacro writes it: `<?xml version="1.0" ?>` and each top-level node, pretty-printed as minidom's
// toprettyxml(indent="  ") with xacro's writexml (attributes sorted by name, whitespace-only text skipped, an
// element whose only child is a text written on one line).
std::string to_pretty_xml(const Node* document);

}  // namespace lcm_control::xacro::dom
