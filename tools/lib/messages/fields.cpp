#include "tools/lib/messages/fields.hpp"
#include "tools/lib/messages/message_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <utility>
#include <type_traits>

#include "bus/bus.hpp"
#include "description/text.hpp"
#include "lcm_control/visit.hpp"

namespace lcm_control::tools {

std::string Field::text() const {
  if (is_text) return str;
  return integer ? std::to_string(exact) : fmt::format("{}", value);
}

namespace {

const FieldInfo* field_info(const std::string& type, const std::string& field) {
  for (const FieldInfo& i : kFieldInfo)
    if (type == i.type && field == i.field) return &i;
  return nullptr;
}

std::vector<std::string> words(const char* text) {
  std::vector<std::string> out;
  std::string w;
  for (const char* c = text; *c; ++c) {
    if (*c != ' ') w += *c;
    if ((*c == ' ' || !c[1]) && !w.empty()) out.push_back(std::exchange(w, {}));
  }
  return out;
}

// Names usable as row labels in a path: non-empty, distinct, none of the path's own characters.
bool labels_ok(const std::vector<std::string>& names) {
  for (size_t k = 0; k < names.size(); ++k) {
    if (names[k].empty() || names[k].find_first_of("[].,\"\r\n ") != std::string::npos) return false;
    if (std::find(names.begin(), names.begin() + long(k), names[k]) != names.begin() + long(k)) return false;
  }
  return true;
}

// A visitor (lcm_control/visit.hpp) that appends a message's numbers and strings as fields under a path prefix.
// A matrix's rows are labelled by the string array the schema says names them (kFieldInfo's labels; link_poses:
// position[rotor].z) when its names can be, its columns by the schema's component names; a list's elements
// keep their index in the path and take the names in their label only (position[0], label position[j1]).
class Flatten {
 public:
  Flatten(std::vector<Field>& f, std::string prefix, std::string type, std::string label_prefix)
      : f_(f), prefix_(std::move(prefix)), label_prefix_(std::move(label_prefix)), type_(std::move(type)) {}
  template <class T>
  void value(const char* name, const T& x) {
    put(prefix_ + name, x, label_prefix_ + name);
  }
  void count(const char*, int32_t) {}  // array lengths are left out
  template <class T>
  void list(const char* name, const std::vector<T>& xs, const char*) {
    if constexpr (std::is_same_v<T, std::string>)
      strings_[name] = &xs;
    const std::vector<std::string>* rows = row_names(name, xs.size());
    for (size_t k = 0; k < xs.size(); ++k)
      put(fmt::format("{}{}[{}]", prefix_, name, k), xs[k],
          fmt::format("{}{}[{}]", label_prefix_, name, rows ? (*rows)[k] : std::to_string(k)));
  }
  template <class T>
  void matrix(const char* name, const std::vector<std::vector<T>>& xs, const char*, int) {
    const FieldInfo* info = field_info(type_, name);
    const std::vector<std::string> cols = info ? words(info->components) : std::vector<std::string>{};
    const auto found = strings_.find(info ? info->labels : "");
    const std::vector<std::string>* rows =
        found != strings_.end() && labels_ok(*found->second) ? found->second : nullptr;
    for (size_t k = 0; k < xs.size(); ++k) {
      const bool named_row = rows && k < rows->size();
      const std::string row = named_row ? (*rows)[k] : std::to_string(k);
      for (size_t j = 0; j < xs[k].size(); ++j) {
        const std::string tail = j < cols.size() && named_row ? fmt::format("{}[{}].{}", name, row, cols[j])
                                                              : fmt::format("{}[{}][{}]", name, row, j);
        put(prefix_ + tail, xs[k][j], label_prefix_ + tail);
      }
    }
  }
  template <class S>
  void structs(const char* name, const std::vector<S>& xs, const char*) {
    const std::vector<std::string>* rows = row_names(name, xs.size());
    for (size_t k = 0; k < xs.size(); ++k) {
      Flatten sub(f_, fmt::format("{}{}[{}].", prefix_, name, k), S::getTypeName(),
                  fmt::format("{}{}[{}].", label_prefix_, name, rows ? (*rows)[k] : std::to_string(k)));
      visit(xs[k], sub);
    }
  }
  template <class S>
  void nested(const char* name, const S& x) {
    Flatten sub(f_, prefix_ + name + ".", S::getTypeName(), label_prefix_ + name + ".");
    visit(x, sub);
  }

 private:
  // The names the schema gives the `size` rows of list `name`, when they can label them; else null.
  const std::vector<std::string>* row_names(const char* name, size_t size) const {
    const FieldInfo* info = field_info(type_, name);
    const auto found = strings_.find(info ? info->labels : "");
    if (found == strings_.end() || found->second->size() != size || !labels_ok(*found->second)) return nullptr;
    return found->second;
  }
  static std::string label_of(std::string path, std::string label) { return label == path ? "" : label; }
  void put(std::string path, double v, std::string label) {
    f_.push_back(Field{path, v, 0, false, false, "", label_of(path, std::move(label))});
  }
  void put(std::string path, float v, std::string label) { put(std::move(path), double(v), std::move(label)); }
  void put(std::string path, const std::string& v, std::string label) {
    f_.push_back(Field{path, 0, 0, false, true, v, label_of(path, std::move(label))});
  }
  template <class I, class = std::enable_if_t<std::is_integral_v<I>>>
  void put(std::string path, I v, std::string label) {
    f_.push_back(Field{path, double(v), int64_t(v), true, false, "", label_of(path, std::move(label))});
  }
  std::vector<Field>& f_;
  std::string prefix_, label_prefix_, type_;
  std::map<std::string, const std::vector<std::string>*> strings_;  // the string arrays visited so far, by field
};

struct TypeEntry {
  int64_t hash;
  const char* name;
  Decoded (*decode)(const void*, size_t);
  const char* skip_reason;  // non-null: known type without signals
};

template <class Msg>
Decoded decode_as(const void* data, size_t size) {
  Decoded d;
  d.type = std::string("lcm_control.") + Msg::getTypeName();
  Msg m{};
  if (!decode_guarded(m, data, size)) {
    d.skip_reason = "malformed payload (decode failed)";
    return d;
  }
  Flatten flat(d.fields, "", Msg::getTypeName(), "");
  visit(m, flat);
  // Strings after all the numbers: a numeric column keeps its position in a file without strings.
  std::stable_partition(d.fields.begin(), d.fields.end(), [](const Field& f) { return !f.is_text; });
  return d;
}

// Types that carry no signal to plot or tabulate; every other type is decoded.
const char* skip_reason(const std::string& type) {
  if (type == cm_request_t::getTypeName()) return "controller-manager request: names and options, no signals (see cmctl)";
  if (type == cm_response_t::getTypeName()) return "controller-manager answer: names and text, no signals (see cmctl list)";
  if (type == controller_info_t::getTypeName()) return "controller description: names only, no numbers";
  if (type == trajectory_point_t::getTypeName()) return "a part of joint_trajectory_t, not sent on its own";
  return nullptr;
}

const std::vector<TypeEntry>& table() {
  static const std::vector<TypeEntry> t = [] {
    std::vector<TypeEntry> out;
    for_each_type([&](auto tag) {
      using Msg = typename decltype(tag)::type;
      const char* skip = skip_reason(Msg::getTypeName());
      out.push_back(TypeEntry{Msg::getHash(), Msg::getTypeName(), skip ? nullptr : &decode_as<Msg>, skip});
    });
    return out;
  }();
  return t;
}

}  // namespace

Decoded decode_fields(const void* data, size_t size) {
  Decoded d;
  if (size < 8) {
    d.skip_reason = fmt::format("payload of {} bytes is too short for an LCM message", size);
    return d;
  }
  const int64_t hash = payload_fingerprint(data);
  for (const auto& e : table()) {
    if (e.hash != hash) continue;
    if (e.decode) return e.decode(data, size);
    d.type = std::string("lcm_control.") + e.name;
    d.skip_reason = e.skip_reason;
    return d;
  }
  d.skip_reason = fmt::format("not an lcm_control type (fingerprint 0x{:016x})", uint64_t(hash));
  return d;
}

std::vector<std::string> known_types() {
  std::vector<std::string> out;
  for (const auto& e : table())
    out.push_back(e.decode ? std::string(e.name) : fmt::format("{} (skipped: {})", e.name, e.skip_reason));
  return out;
}

std::string csv_file_name(const std::string& channel) {
  std::string s;
  for (char c : channel) s += c == '/' ? std::string("__") : std::string(1, c);
  while (!s.empty() && s[0] == '_') s.erase(0, 1);
  return (s.empty() ? std::string("channel") : s) + ".csv";
}

std::vector<const Field*> select_fields(const std::vector<Field>& fields, const std::string& wanted) {
  const std::string w = wanted.substr(std::min(wanted.size(), wanted.find_first_not_of("./")));
  std::vector<const Field*> out;
  for (const Field& f : fields)
    if (f.path == w || f.label == w) return {&f};
  auto under = [&](const std::string& name) {
    return name.size() > w.size() && name.compare(0, w.size(), w) == 0 && (name[w.size()] == '[' || name[w.size()] == '.');
  };
  for (const Field& f : fields)
    if (!w.empty() && (under(f.path) || under(f.label))) out.push_back(&f);
  return out;
}

std::vector<std::string> nearest_fields(const std::vector<Field>& fields, const std::string& wanted, size_t most) {
  std::vector<std::string> names;
  for (const Field& f : fields) {
    if (f.is_text) continue;
    for (const std::string& n : {f.name(), f.path}) {
      for (size_t cut = n.find_first_of("[."); cut != std::string::npos; cut = n.find_first_of("[.", cut + 1))
        names.push_back(n.substr(0, cut));  // what holds it: position, points[0].positions
      names.push_back(n);
    }
  }
  return closest_names(wanted, names, most, std::max<size_t>(3, wanted.size() / 2));
}

std::string field_unit(const std::string& type, const std::string& path) {
  std::string t = short_type_name(type);
  size_t at = 0;
  while (at < path.size()) {
    const size_t end = path.find_first_of(".[", at);
    const FieldInfo* info = field_info(t, path.substr(at, end - at));
    if (!info) return "";
    if (!*info->nested) return info->unit;
    t = info->nested;  // a nested message: its field follows the next '.'
    at = path.find('.', end == std::string::npos ? path.size() : end);
    at = at == std::string::npos ? path.size() : at + 1;
  }
  return "";
}

}  // namespace lcm_control::tools
