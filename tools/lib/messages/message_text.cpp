#include "tools/lib/messages/message_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <limits>
#include <map>
#include <stdexcept>
#include <type_traits>

#include "bus/bus.hpp"
#include "lcm_control/visit.hpp"
#include "rt/escape.hpp"

namespace lcm_control::tools {
namespace {

// Calls f(type_tag<Msg>) for the type whose short name ("joint_state_t") is `name`; false if none is.
template <class F>
bool with_type_named(const std::string& name, F&& f) {
  bool found = false;
  for_each_type([&](auto tag) {
    using Msg = typename decltype(tag)::type;
    if (!found && name == Msg::getTypeName()) {
      found = true;
      f(tag);
    }
  });
  return found;
}

template <class F>
bool with_type_hash(int64_t hash, F&& f) {
  bool found = false;
  for_each_type([&](auto tag) {
    using Msg = typename decltype(tag)::type;
    if (!found && hash == Msg::getHash()) {
      found = true;
      f(tag);
    }
  });
  return found;
}


// --- text ----------------------------------------------------------------------------------------------------

bool plain_yaml(const std::string& s) {
  if (s.empty() || s == "true" || s == "false" || s == "null" || s == "~") return false;
  if (std::string("-?:,[]{}#&*!|>'\"%@` ").find(s.front()) != std::string::npos || s.back() == ' ') return false;
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  if (end && *end == '\0') return false;  // would read back as a number
  for (unsigned char c : s)
    if (c < 0x20 || c == 0x7f || c == '#' || c == ':' || c == ',' || c == '[' || c == ']') return false;
  return true;
}

std::string scalar_text(const std::string& s) {
  if (plain_yaml(s)) return s;
  return "\"" + escape_controls(s, false, "\"\\") + "\"";
}
std::string scalar_text(double v) { return fmt::format("{}", v); }
[[maybe_unused]] std::string scalar_text(float v) { return fmt::format("{}", v); }
template <class I, class = std::enable_if_t<std::is_integral_v<I>>>
std::string scalar_text(I v) {
  return std::to_string(int64_t(v));
}

template <class T>
std::string flow_list(const std::vector<T>& xs) {
  std::string out = "[";
  for (size_t k = 0; k < xs.size(); ++k) out += (k ? ", " : "") + scalar_text(xs[k]);
  return out + "]";
}

// Writes fields as YAML-like lines at an indent; the first line of a list item starts with "- ".
class Yaml {
 public:
  Yaml(std::string& out, int indent, bool item = false) : out_(out), indent_(indent), item_(item) {}
  template <class T>
  void value(const char* name, const T& x) {
    line(std::string(name) + ": " + scalar_text(x));
  }
  void count(const char*, int32_t) {}
  template <class T>
  void list(const char* name, const std::vector<T>& xs, const char*) {
    line(std::string(name) + ": " + flow_list(xs));
  }
  template <class T>
  void matrix(const char* name, const std::vector<std::vector<T>>& xs, const char*, int) {
    std::string rows = "[";
    for (size_t k = 0; k < xs.size(); ++k) rows += (k ? ", " : "") + flow_list(xs[k]);
    line(std::string(name) + ": " + rows + "]");
  }
  template <class S>
  void structs(const char* name, const std::vector<S>& xs, const char*) {
    if (xs.empty()) return line(std::string(name) + ": []");
    line(std::string(name) + ":");
    for (const auto& x : xs) {
      Yaml sub(out_, indent_ + 2, true);
      visit(x, sub);
    }
  }
  template <class S>
  void nested(const char* name, const S& x) {
    line(std::string(name) + ":");
    Yaml sub(out_, indent_ + 2);
    visit(x, sub);
  }

 private:
  void line(const std::string& text) {
    if (item_) {
      out_ += std::string(size_t(indent_ - 2), ' ') + "- " + text + "\n";
      item_ = false;
    } else {
      out_ += std::string(size_t(indent_), ' ') + text + "\n";
    }
  }
  std::string& out_;
  int indent_;
  bool item_;
};

// --- fields of a type ----------------------------------------------------------------------------------------

const char* kind(double) { return "double"; }
[[maybe_unused]] const char* kind(float) { return "float"; }
const char* kind(int64_t) { return "int64"; }
const char* kind(int32_t) { return "int32"; }
[[maybe_unused]] const char* kind(int16_t) { return "int16"; }
const char* kind(int8_t) { return "int8 or boolean"; }
[[maybe_unused]] const char* kind(uint8_t) { return "byte"; }
const char* kind(const std::string&) { return "string"; }

class Describe {
 public:
  Describe(std::vector<std::string>& out, std::string prefix) : out_(out), prefix_(std::move(prefix)) {}
  template <class T>
  void value(const char* name, const T& x) {
    out_.push_back(fmt::format("{}{} ({})", prefix_, name, kind(x)));
  }
  void count(const char*, int32_t) {}
  template <class T>
  void list(const char* name, const std::vector<T>&, const char*) {
    out_.push_back(fmt::format("{}{}[] ({})", prefix_, name, kind(T{})));
  }
  template <class T>
  void matrix(const char* name, const std::vector<std::vector<T>>&, const char*, int inner) {
    out_.push_back(fmt::format("{}{}[][{}] ({})", prefix_, name, inner, kind(T{})));
  }
  template <class S>
  void structs(const char* name, const std::vector<S>&, const char*) {
    Describe sub(out_, fmt::format("{}{}[].", prefix_, name));
    const S x{};
    visit(x, sub);
  }
  template <class S>
  void nested(const char* name, const S& x) {
    Describe sub(out_, fmt::format("{}{}.", prefix_, name));
    visit(x, sub);
  }

 private:
  std::vector<std::string>& out_;
  std::string prefix_;
};

// --- building from assignments -------------------------------------------------------------------------------

struct Segment {
  std::string name;
  std::vector<size_t> index;
};

constexpr size_t kMaxIndex = 100000;  // an array of a message built on the command line

std::vector<Segment> parse_path(const std::string& path) {
  std::vector<Segment> out;
  size_t i = 0;
  auto bad = [&](const std::string& why) { throw std::invalid_argument(fmt::format("'{}': {}", path, why)); };
  while (true) {
    Segment s;
    while (i < path.size() && (std::isalnum(static_cast<unsigned char>(path[i])) || path[i] == '_')) s.name += path[i++];
    if (s.name.empty()) bad("expected a field name at character " + std::to_string(i + 1));
    while (i < path.size() && path[i] == '[') {
      const size_t close = path.find(']', i);
      if (close == std::string::npos) bad("'[' without ']'");
      const std::string digits = path.substr(i + 1, close - i - 1);
      if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 6)
        bad("index '" + digits + "' is not a number from 0 to " + std::to_string(kMaxIndex - 1));
      const size_t k = std::stoul(digits);
      if (k >= kMaxIndex) bad("index " + digits + " is too large");
      s.index.push_back(k);
      i = close + 1;
    }
    out.push_back(std::move(s));
    if (i == path.size()) return out;
    if (path[i] != '.') bad(fmt::format("unexpected '{}' at character {}", path[i], i + 1));
    ++i;
  }
}

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

// "[a, b]" or "a,b" -> {"a", "b"}; "[]" -> {}. Surrounding double quotes are removed from each item.
std::vector<std::string> split_list(std::string v) {
  v = trim(v);
  if (v.size() >= 2 && v.front() == '[' && v.back() == ']') v = v.substr(1, v.size() - 2);
  std::vector<std::string> out;
  if (trim(v).empty()) return out;
  size_t start = 0;
  while (true) {
    const size_t comma = v.find(',', start);
    std::string item = trim(v.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (item.size() >= 2 && item.front() == '"' && item.back() == '"') item = item.substr(1, item.size() - 2);
    out.push_back(item);
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

void parse_into(const std::string& text, std::string& x) { x = text; }
void parse_into(const std::string& text, double& x) {
  const std::string t = trim(text);
  char* end = nullptr;
  errno = 0;
  x = std::strtod(t.c_str(), &end);
  if (t.empty() || *end != '\0') throw std::invalid_argument("'" + text + "' is not a number");
}
[[maybe_unused]] void parse_into(const std::string& text, float& x) {
  double d = 0;
  parse_into(text, d);
  x = float(d);
}
template <class I, class = std::enable_if_t<std::is_integral_v<I>>>
void parse_into(const std::string& text, I& x) {
  const std::string t = trim(text);
  if (t == "true" || t == "false") {
    x = I(t == "true");
    return;
  }
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(t.c_str(), &end, 10);
  if (t.empty() || *end != '\0' || errno == ERANGE) throw std::invalid_argument("'" + text + "' is not an integer");
  if (v < std::numeric_limits<I>::min() || v > std::numeric_limits<I>::max())
    throw std::invalid_argument(fmt::format("{} is out of range for {} ({} to {})", v, kind(I{}),
                                            int64_t(std::numeric_limits<I>::min()),
                                            int64_t(std::numeric_limits<I>::max())));
  x = I(v);
}

template <class T>
void parse_list(const std::string& text, std::vector<T>& xs) {
  const auto items = split_list(text);
  xs.assign(items.size(), T{});
  for (size_t k = 0; k < items.size(); ++k) parse_into(items[k], xs[k]);
}

// Applies one assignment (the path from segment `at` on) to a message.
class Assign {
 public:
  Assign(std::vector<Segment> path, size_t at, std::string value)
      : path_(std::move(path)), at_(at), value_(std::move(value)) {}
  bool found() const { return found_; }

  template <class T>
  void value(const char* name, T& x) {
    if (!mine(name)) return;
    no_index(name);
    no_fields(name);
    parse_into(value_, x);
  }
  void count(const char* name, int32_t&) {
    if (!mine(name)) return;
    throw std::invalid_argument(std::string(name) + " is set from the length of the arrays it sizes; assign those");
  }
  template <class T>
  void list(const char* name, std::vector<T>& xs, const char*) {
    if (!mine(name)) return;
    no_fields(name);
    const auto& idx = seg().index;
    if (idx.empty()) return parse_list(value_, xs);
    if (idx.size() > 1) throw std::invalid_argument(std::string(name) + " has one index");
    if (xs.size() <= idx[0]) xs.resize(idx[0] + 1);
    parse_into(value_, xs[idx[0]]);
  }
  template <class T>
  void matrix(const char* name, std::vector<std::vector<T>>& xs, const char*, int inner) {
    if (!mine(name)) return;
    no_fields(name);
    const auto& idx = seg().index;
    if (idx.empty() || idx.size() > 2)
      throw std::invalid_argument(fmt::format("give {0}[ROW]=[{1} values] or {0}[ROW][COLUMN]=VALUE", name, inner));
    if (xs.size() <= idx[0]) xs.resize(idx[0] + 1);
    auto& row = xs[idx[0]];
    if (idx.size() == 1) {
      parse_list(value_, row);
      if (row.size() != size_t(inner))
        throw std::invalid_argument(fmt::format("{}[{}] has {} values; its rows have {}", name, idx[0], row.size(), inner));
      return;
    }
    if (idx[1] >= size_t(inner)) throw std::invalid_argument(fmt::format("{}'s rows have {} columns", name, inner));
    row.resize(size_t(inner));
    parse_into(value_, row[idx[1]]);
  }
  template <class S>
  void structs(const char* name, std::vector<S>& xs, const char*) {
    if (!mine(name)) return;
    const auto& idx = seg().index;
    if (idx.size() != 1 || last())
      throw std::invalid_argument(fmt::format("give a field of one element: {}[K].FIELD=VALUE", name));
    if (xs.size() <= idx[0]) xs.resize(idx[0] + 1);
    descend(xs[idx[0]]);
  }
  template <class S>
  void nested(const char* name, S& x) {
    if (!mine(name)) return;
    no_index(name);
    if (last()) throw std::invalid_argument(fmt::format("give a field of it: {}.FIELD=VALUE", name));
    descend(x);
  }

 private:
  const Segment& seg() const { return path_[at_]; }
  bool mine(const char* name) {
    if (found_ || seg().name != name) return false;
    found_ = true;
    return true;
  }
  bool last() const { return at_ + 1 == path_.size(); }
  void no_index(const char* name) const {
    if (!seg().index.empty()) throw std::invalid_argument(std::string(name) + " is not an array");
  }
  void no_fields(const char* name) const {
    if (!last()) throw std::invalid_argument(std::string(name) + " has no fields");
  }
  template <class S>
  void descend(S& x) {
    Assign sub(path_, at_ + 1, value_);
    visit(x, sub);
    if (!sub.found()) throw std::invalid_argument("no field '" + path_[at_ + 1].name + "' in " + S::getTypeName());
  }
  std::vector<Segment> path_;
  size_t at_;
  std::string value_;
  bool found_ = false;
};

// Sets every array count from its arrays' lengths, checking that arrays sized by one count agree.
class Counts {
 public:
  explicit Counts(const char* type) : type_(type) {}
  template <class T>
  void value(const char*, T&) {}
  void count(const char* name, int32_t& n) {
    if (set_) n = int32_t(sizes_[name].second);
  }
  template <class V>
  void list(const char* name, V& xs, const char* counter) {
    seen(name, xs.size(), counter);
  }
  template <class T>
  void matrix(const char* name, std::vector<std::vector<T>>& xs, const char* counter, int inner) {
    seen(name, xs.size(), counter);
    if (set_)
      for (auto& row : xs) row.resize(size_t(inner));
  }
  template <class S>
  void structs(const char* name, std::vector<S>& xs, const char* counter) {
    seen(name, xs.size(), counter);
    if (set_)
      for (auto& x : xs) fill_counts(x);
  }
  template <class S>
  void nested(const char*, S& x) {
    if (set_) fill_counts(x);
  }
  template <class Msg>
  static void fill_counts(Msg& m) {
    Counts c(Msg::getTypeName());
    visit(m, c);
    c.set_ = true;
    visit(m, c);
  }

 private:
  void seen(const char* name, size_t n, const char* counter) {
    if (set_) return;
    auto [it, fresh] = sizes_.emplace(counter, std::make_pair(std::string(name), n));
    if (!fresh && it->second.second != n)
      throw std::invalid_argument(fmt::format("{}: {} has {} values but {} has {}; arrays sized by {} must be as long",
                                              type_, name, n, it->second.first, it->second.second, counter));
  }
  const char* type_;
  std::map<std::string, std::pair<std::string, size_t>> sizes_;  // count -> (first array, its length)
  bool set_ = false;
};

std::string list_text(const std::vector<std::string>& xs) {
  std::string out;
  for (const auto& x : xs) out += (out.empty() ? "" : ", ") + x;
  return out;
}

}  // namespace

std::string short_type_name(std::string type) {
  if (type.rfind("lcm_control.", 0) == 0) type.erase(0, 12);
  if (type.size() < 2 || type.compare(type.size() - 2, 2, "_t") != 0) type += "_t";
  return type;
}

std::string type_of_payload(const void* data, size_t size) {
  std::string out;
  if (size >= 8)
    with_type_hash(payload_fingerprint(data), [&](auto tag) {
      out = std::string("lcm_control.") + decltype(tag)::type::getTypeName();
    });
  return out;
}

std::vector<std::string> message_type_names() {
  std::vector<std::string> out;
  for_each_type([&](auto tag) { out.push_back(decltype(tag)::type::getTypeName()); });
  std::sort(out.begin(), out.end());
  return out;
}

std::string message_yaml(const void* data, size_t size) {
  if (size < 8) throw std::runtime_error(fmt::format("{} bytes are too short for an LCM message", size));
  std::string out;
  bool decoded = false;
  const bool known = with_type_hash(payload_fingerprint(data), [&](auto tag) {
    typename decltype(tag)::type m{};
    if (!decode_guarded(m, data, size)) return;
    decoded = true;
    Yaml y(out, 0);
    visit(m, y);
  });
  if (!known)
    throw std::runtime_error(fmt::format("not an lcm_control type (fingerprint 0x{:016x})", uint64_t(payload_fingerprint(data))));
  if (!decoded) throw std::runtime_error(type_of_payload(data, size) + ": malformed payload (decode failed)");
  return out;
}

std::vector<std::string> message_fields(const std::string& type) {
  std::vector<std::string> out;
  const std::string name = short_type_name(type);
  if (!with_type_named(name, [&](auto tag) {
        Describe d(out, "");
        const typename decltype(tag)::type m{};
        visit(m, d);
      }))
    throw std::invalid_argument(fmt::format("unknown message type '{}'; the types are: {}", type,
                                            list_text(message_type_names())));
  return out;
}

std::vector<uint8_t> build_message(const std::string& type, const std::vector<std::string>& assignments,
                                   int64_t default_utime) {
  const std::string name = short_type_name(type);
  std::vector<uint8_t> bytes;
  const bool known = with_type_named(name, [&](auto tag) {
    using Msg = typename decltype(tag)::type;
    Msg m{};
    bool utime_set = false;
    for (const auto& a : assignments) {
      const size_t eq = a.find('=');
      if (eq == std::string::npos || eq == 0)
        throw std::invalid_argument(fmt::format("'{}' is not FIELD=VALUE; {}'s fields: {}", a, name,
                                                list_text(message_fields(name))));
      const std::string path = trim(a.substr(0, eq));
      try {
        const auto segments = parse_path(path);
        Assign set(segments, 0, a.substr(eq + 1));
        visit(m, set);
        if (!set.found()) throw std::invalid_argument("no such field");
        utime_set = utime_set || (segments.size() == 1 && segments[0].name == "utime");
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(fmt::format("{}: {}: {}; its fields: {}", name, path, e.what(),
                                                list_text(message_fields(name))));
      }
    }
    const auto fields = message_fields(name);
    if (!utime_set && std::find(fields.begin(), fields.end(), "utime (int64)") != fields.end()) {
      Assign set(parse_path("utime"), 0, std::to_string(default_utime));
      visit(m, set);
    }
    Counts::fill_counts(m);
    const int n = m.getEncodedSize();
    bytes.resize(size_t(n));
    if (m.encode(bytes.data(), 0, n) != n) throw std::invalid_argument(name + ": the message does not encode");
  });
  if (!known)
    throw std::invalid_argument(fmt::format("unknown message type '{}'; the types are: {}", type,
                                            list_text(message_type_names())));
  return bytes;
}

}  // namespace lcm_control::tools
