// Hostile LCM payloads from a seed, for the fuzz tests: well-formed messages of
// every type filled with NaN / Inf / 1e308 / -0 / denormals, empty, duplicate,
// unknown and 60 KB names, then (half of the time) mutated on the wire: random
// bytes, truncation, extension, a wrong fingerprint, array counts made huge,
// negative or not matching, and bit flips.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "lcm_control/visit.hpp"

namespace lcm_control::testing {

// Values a fuzzed field is drawn from besides random ones: names the receiver knows, its live session and step.
struct Hints {
  std::vector<std::string> names;
  std::vector<int64_t> integers;
};

class Payloads {
 public:
  explicit Payloads(uint64_t seed) : rng_(seed) {}

  // A payload for a channel whose receiver expects Msg: Msg most of the time, another type sometimes.
  template <class Msg>
  std::vector<uint8_t> next(const Hints& hints) {
    std::vector<uint8_t> b;
    if (pick(10) == 0) {
      b = random_bytes(pick(3) == 0 ? 0 : 1 + pick(400));
      kind_ = "random bytes";
      return b;
    }
    if (pick(8) == 0)
      b = any_type(hints);
    else
      b = well_formed<Msg>(hints);
    if (pick(2) == 0) mutate(b, hints);
    return b;
  }
  const char* kind() const { return kind_; }

  template <class Msg>
  std::vector<uint8_t> well_formed(const Hints& hints) {
    Msg m{};
    Fill f{*this, hints};
    visit(m, f);
    Counts c;
    visit(m, c);
    kind_ = "well-formed, hostile values";
    return encode(m);
  }

  uint64_t pick(uint64_t n) { return n == 0 ? 0 : rng_() % n; }

 private:
  template <class Msg>
  static std::vector<uint8_t> encode(const Msg& m) {
    std::vector<uint8_t> b(size_t(m.getEncodedSize()));
    m.encode(b.data(), 0, int(b.size()));
    return b;
  }

  std::vector<uint8_t> any_type(const Hints& hints) {
    const uint64_t want = pick(19);
    uint64_t k = 0;
    std::vector<uint8_t> out;
    for_each_type([&](auto tag) {
      if (k++ == want) out = well_formed<typename decltype(tag)::type>(hints);
    });
    if (out.empty()) out = random_bytes(16);
    kind_ = "another type";
    return out;
  }

  std::vector<uint8_t> random_bytes(size_t n) {
    std::vector<uint8_t> b(n);
    for (auto& x : b) x = uint8_t(rng_());
    return b;
  }

  void mutate(std::vector<uint8_t>& b, const Hints& hints) {
    switch (pick(6)) {
      case 0:
        b.resize(b.empty() ? 0 : pick(b.size()));
        kind_ = "truncated";
        break;
      case 1: {
        const auto tail = random_bytes(1 + pick(64));
        b.insert(b.end(), tail.begin(), tail.end());
        kind_ = "extended";
        break;
      }
      case 2:
        if (!b.empty()) b[pick(std::min<size_t>(8, b.size()))] ^= uint8_t(1 + pick(255));
        kind_ = "wrong fingerprint";
        break;
      case 3: {  // an int32 somewhere (array counts are int32) made huge, negative or off by some
        if (b.size() < 12) break;
        const size_t at = 8 + pick(b.size() - 11);
        const int32_t values[] = {-1, std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::max(),
                                  67108866, int32_t(b.size()), int32_t(pick(8)), 1 << 20};
        const int32_t v = values[pick(7)];
        for (int k = 0; k < 4; ++k) b[at + size_t(k)] = uint8_t(uint32_t(v) >> (24 - 8 * k));
        kind_ = "array count forged";
        break;
      }
      case 4:
        for (uint64_t k = 0, n = 1 + pick(8); k < n && !b.empty(); ++k) b[pick(b.size())] ^= uint8_t(1u << pick(8));
        kind_ = "bit flips";
        break;
      default: {  // a known string spliced in where bytes were
        if (hints.names.empty() || b.size() < 16) break;
        const std::string& s = hints.names[pick(hints.names.size())];
        const size_t at = 8 + pick(b.size() - 8);
        for (size_t k = 0; k < s.size() && at + k < b.size(); ++k) b[at + k] = uint8_t(s[k]);
        kind_ = "name spliced";
      }
    }
  }

  double number() {
    static const double special[] = {std::numeric_limits<double>::quiet_NaN(),
                                     std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(),
                                     1e308,
                                     -1e308,
                                     -0.0,
                                     5e-324,
                                     0.0,
                                     1.0,
                                     0.5};
    if (pick(3) == 0) return special[pick(10)];
    return (double(pick(2000001)) - 1000000.0) * 1e-4;
  }
  int64_t integer(const Hints& h) {
    if (!h.integers.empty() && pick(2) == 0) return h.integers[pick(h.integers.size())] + int64_t(pick(3)) - 1;
    static const int64_t special[] = {0, 1, -1, std::numeric_limits<int64_t>::max(), std::numeric_limits<int64_t>::min(),
                                      1000, 1 << 30};
    return pick(2) ? special[pick(7)] : int64_t(pick(100));
  }
  std::string text(const Hints& h) {
    switch (pick(6)) {
      case 0:
        return "";
      case 1:
        return std::string(60000, char('a' + pick(26)));
      case 2:
        return "unknown_" + std::to_string(pick(1000));
      case 3:
        return std::string("\n\t\"'%s{}\x01", 9);
      default:
        return h.names.empty() ? "x" : h.names[pick(h.names.size())];
    }
  }

  // Fills every field with hostile values; arrays of 0 to 4 elements, sometimes 50.
  struct Fill {
    Payloads& p;
    const Hints& h;
    template <class T>
    void value(const char*, T& x) {
      set(x);
    }
    void count(const char*, int32_t&) {}
    template <class T>
    void list(const char*, std::vector<T>& xs, const char*) {
      xs.resize(p.pick(10) == 0 ? 50 : p.pick(5));
      for (auto& x : xs) set(x);
    }
    template <class T>
    void matrix(const char*, std::vector<std::vector<T>>& xs, const char*, int inner) {
      xs.resize(p.pick(4));
      for (auto& row : xs) {
        row.resize(size_t(inner));
        for (auto& x : row) set(x);
      }
    }
    template <class S>
    void structs(const char*, std::vector<S>& xs, const char*) {
      xs.resize(p.pick(4));
      for (auto& x : xs) visit(x, *this);
    }
    template <class S>
    void nested(const char*, S& x) {
      visit(x, *this);
    }
    void set(double& x) { x = p.number(); }
    void set(float& x) { x = float(p.number()); }
    void set(std::string& x) { x = p.text(h); }
    template <class I>
    void set(I& x) {
      x = I(p.integer(h));
    }
  };

  // Array counts from the arrays (arrays sized by one count made as long as the first of them), so that lcm-gen's
  // encoder reads only what is there; the wire mutations forge counts.
  struct Counts {
    std::vector<std::pair<std::string, int32_t*>> counts;
    std::vector<std::string> sized;
    template <class T>
    void value(const char*, T&) {}
    void count(const char* name, int32_t& n) { counts.emplace_back(name, &n); }
    template <class V>
    void list(const char*, V& xs, const char* counter) {
      size(xs, counter);
    }
    template <class T>
    void matrix(const char*, std::vector<std::vector<T>>& xs, const char* counter, int inner) {
      size(xs, counter);
      for (auto& row : xs) row.resize(size_t(inner));
    }
    template <class S>
    void structs(const char*, std::vector<S>& xs, const char* counter) {
      size(xs, counter);
      for (auto& x : xs) {
        Counts inner;
        visit(x, inner);
      }
    }
    template <class S>
    void nested(const char*, S& x) {
      Counts inner;
      visit(x, inner);
    }
    template <class V>
    void size(V& xs, const std::string& counter) {
      for (auto& [name, n] : counts) {
        if (name != counter) continue;
        if (std::find(sized.begin(), sized.end(), counter) == sized.end()) {
          *n = int32_t(xs.size());
          sized.push_back(counter);
        } else {
          xs.resize(size_t(*n));
        }
      }
    }
  };

  std::mt19937_64 rng_;
  const char* kind_ = "";
};

}  // namespace lcm_control::testing
