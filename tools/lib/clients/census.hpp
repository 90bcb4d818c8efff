// Every channel on the bus (or in the namespace), counted: what `bus list`
// shows, and what a tool that waited in vain says it did see.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "bus/bus.hpp"

namespace lcm_control::tools {

// What was seen on one channel: count, bytes, first and last receive time, type.
struct ChannelSeen {
  int64_t count = 0, bytes = 0, first_us = 0, last_us = 0;
  std::string type;
  double rate(int64_t window_us) const {
    if (count >= 2 && last_us > first_us) return double(count - 1) * 1e6 / double(last_us - first_us);
    return window_us > 0 ? double(count) * 1e6 / double(window_us) : 0;
  }
};

// The lcm_control type a payload carries ("? (N bytes)" or "? 0x<fingerprint>" for others).
std::string type_name(const void* data, size_t size);

class Census {
 public:
  explicit Census(Bus& bus);
  Census(const Census&) = delete;
  Census& operator=(const Census&) = delete;
  // The first kMaxChannels channels heard; messages on others are only counted (docs/reliability.md, "Limits").
  static constexpr size_t kMaxChannels = 1000;
  const std::map<std::string, ChannelSeen>& seen() const { return seen_; }
  int64_t unlisted() const { return unlisted_; }  // messages on channels over kMaxChannels
  std::string names() const;  // "a, b, c", or "none"

 private:
  void on(const lcm::ReceiveBuffer* rb, const std::string& channel);
  std::map<std::string, ChannelSeen> seen_;
  int64_t unlisted_ = 0;
};

// A robot's own channels heard in other namespaces, for the hint a tool that hears nothing in its own gives at once:
// "did you mean --namespace rrbot?" when `rrbot/joint_states` is heard and `joint_states` is not.
class NamespaceProbe {
 public:
  // channels: without a namespace (joint_states, controller_manager/statistics); listens to every channel.
  NamespaceProbe(Bus& bus, std::vector<std::string> channels);
  ~NamespaceProbe();  // unsubscribes
  NamespaceProbe(const NamespaceProbe&) = delete;
  NamespaceProbe& operator=(const NamespaceProbe&) = delete;
  // "did you mean --namespace NS? (heard NS/CHANNEL)" when the channels were heard under one other namespace and not
  // in the tool's own; "did you mean no --namespace? ..." when heard without one; else "".
  std::string hint() const;

 private:
  void on(const lcm::ReceiveBuffer* rb, const std::string& channel);
  Bus& bus_;
  std::vector<std::string> channels_;
  int sub_ = 0;
  bool ours_ = false;
  std::map<std::string, std::string> others_;  // namespace ("" for none) -> a channel heard there
};

}  // namespace lcm_control::tools
