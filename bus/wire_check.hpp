// Walks an LCM payload along its type's schema (lcm_control/visit.hpp) before
// lcm-gen's decoder sees it: lcm-gen trusts every array count and string
// length on the wire, so one forged count makes it allocate millions of
// elements before it finds the buffer too short. The walk allocates nothing
// and reads each byte at most once.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "lcm_control/visit.hpp"

namespace lcm_control {

// An unsigned integer as LCM puts it on the wire (big-endian); the caller checks that the bytes are there.
template <class U>
inline U read_be(const void* p) {
  const auto* b = static_cast<const uint8_t*>(p);
  U v = 0;
  for (size_t k = 0; k < sizeof(U); ++k) v = U(v << 8 | b[k]);
  return v;
}
inline int64_t read_int64_be(const void* p) { return int64_t(read_be<uint64_t>(p)); }

// The type fingerprint in an LCM payload's first 8 bytes.
inline int64_t payload_fingerprint(const void* data) { return read_int64_be(data); }

namespace detail {

class WireWalk {
 public:
  // What stopped the walk: nothing, the bytes ran out, a count beyond [0, max_count], or a malformed string.
  enum class Fault { None, Short, Count, String };

  WireWalk(const uint8_t* data, size_t size, int32_t max_count) : p_(data), left_(size), max_count_(max_count) {}
  bool ok() const { return ok_; }
  size_t left() const { return left_; }
  Fault fault() const { return fault_; }
  // The last array count read (nullptr before any), for the reason.
  const char* last_count() const { return last_count_; }
  int32_t last_value() const { return last_value_; }

  template <class T>
  void value(const char*, const T& x) {
    scalar(x);
  }
  void count(const char* name, const int32_t&) {
    int32_t n = 0;
    if (!read_int32(n)) return;
    last_count_ = name;
    last_value_ = n;
    if (n < 0 || n > max_count_) return fail(Fault::Count);
    if (num_counts_ == counts_.size()) return fail(Fault::Short);
    counts_[num_counts_++] = {name, n};
  }
  template <class T>
  void list(const char*, const std::vector<T>&, const char* counter) {
    const int64_t n = count_of(counter);
    if (!ok_) return;
    if constexpr (std::is_same_v<T, std::string>) {
      for (int64_t k = 0; k < n && ok_; ++k) scalar(std::string());
    } else {
      skip(uint64_t(n) * sizeof(T));
    }
  }
  template <class T>
  void matrix(const char*, const std::vector<std::vector<T>>&, const char* counter, int inner) {
    const int64_t n = count_of(counter);
    if (ok_) skip(uint64_t(n) * uint64_t(inner) * sizeof(T));
  }
  template <class S>
  void structs(const char*, const std::vector<S>&, const char* counter) {
    const int64_t n = count_of(counter);
    const S empty{};
    for (int64_t k = 0; k < n && ok_; ++k) nested("", empty);
  }
  template <class S>
  void nested(const char*, const S& x) {
    WireWalk inner(p_, left_, max_count_);
    visit(x, inner);
    if (inner.last_count_) {
      last_count_ = inner.last_count_;
      last_value_ = inner.last_value_;
    }
    if (!inner.ok_) return fail(inner.fault_);
    p_ += left_ - inner.left_;
    left_ = inner.left_;
  }

 private:
  void fail(Fault f = Fault::Short) {
    if (ok_) fault_ = f;
    ok_ = false;
    left_ = 0;
  }
  void skip(uint64_t n) {
    if (!ok_ || n > left_) return fail();
    p_ += n;
    left_ -= size_t(n);
  }
  bool read_int32(int32_t& v) {
    if (!ok_ || left_ < 4) {
      fail();
      return false;
    }
    v = int32_t(read_be<uint32_t>(p_));
    skip(4);
    return true;
  }
  void scalar(const std::string&) {
    int32_t len = 0;
    if (!read_int32(len)) return;
    // The length counts the terminating NUL. A NUL inside would decode, but lcm-gen encodes strings up to their
    // first NUL while it sizes them by length: such a message could not be sent on again.
    if (len < 1 || uint64_t(len) > left_) return fail();
    if (p_[len - 1] != 0 || std::memchr(p_, 0, size_t(len - 1))) return fail(Fault::String);
    skip(uint64_t(len));
  }
  template <class T>
  void scalar(const T&) {
    skip(sizeof(T));
  }
  int64_t count_of(const char* counter) {
    for (size_t k = 0; k < num_counts_; ++k)
      if (std::strcmp(counts_[k].first, counter) == 0) return counts_[k].second;
    fail();
    return 0;
  }

  const uint8_t* p_;
  size_t left_;
  int32_t max_count_;
  bool ok_ = true;
  Fault fault_ = Fault::None;
  const char* last_count_ = nullptr;
  int32_t last_value_ = 0;
  std::array<std::pair<const char*, int32_t>, 8> counts_{};  // this struct's array counts so far (no allocation)
  size_t num_counts_ = 0;
};

}  // namespace detail

// "" when `size` bytes can be a Msg as far as its counts and lengths go: the fingerprint matches, every array count
// is between 0 and max_count, every array and string fits in the bytes that follow, and every string is
// NUL-terminated with no NUL inside. Else why not, naming the count at fault; `bound_of` says what max_count is
// ("the robot's actuators"). No allocation when the answer is "".
template <class Msg>
std::string wire_problem(const void* data, size_t size, int32_t max_count = INT32_MAX, const char* bound_of = nullptr) {
  auto too_short = [&] { return std::to_string(size) + " bytes: too short for a " + Msg::getTypeName(); };
  if (size < 8) return too_short();
  if (payload_fingerprint(data) != Msg::getHash()) return std::string("not a ") + Msg::getTypeName();
  detail::WireWalk walk(static_cast<const uint8_t*>(data) + 8, size - 8, max_count);
  static const Msg empty{};
  visit(empty, walk);
  using Fault = detail::WireWalk::Fault;
  if (walk.fault() == Fault::None) return {};
  if (walk.fault() == Fault::String) return "a string is not NUL-terminated or holds a NUL";
  if (!walk.last_count()) return too_short();
  const std::string count = std::string(walk.last_count()) + " " + std::to_string(walk.last_value());
  if (walk.fault() == Fault::Count)
    return count + " is not between 0 and " + std::to_string(max_count) +
           (bound_of ? std::string(" (") + bound_of + ")" : std::string());
  return count + " does not fit in " + std::to_string(size) + " bytes";
}

// wire_problem() without the reason: true when lcm-gen's decoder may see the bytes.
template <class Msg>
bool wire_fits(const void* data, size_t size) noexcept {
  if (size < 8 || payload_fingerprint(data) != Msg::getHash()) return false;
  detail::WireWalk walk(static_cast<const uint8_t*>(data) + 8, size - 8, INT32_MAX);
  static const Msg empty{};
  visit(empty, walk);
  return walk.ok();
}

}  // namespace lcm_control
