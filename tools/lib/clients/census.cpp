#include "tools/lib/clients/census.hpp"

#include <fmt/format.h>

#include "bus/wire_check.hpp"
#include "tools/lib/messages/message_text.hpp"
#include "tools/lib/messages/names.hpp"

namespace lcm_control::tools {

std::string type_name(const void* data, size_t size) {
  const std::string t = type_of_payload(data, size);
  if (!t.empty()) return t;
  if (size < 8) return fmt::format("? ({} bytes)", size);
  return fmt::format("? 0x{:016x}", uint64_t(payload_fingerprint(data)));
}

Census::Census(Bus& bus) {
  bus.subscribe(regex_escape(bus.channel("")) + ".*", &Census::on, this, Bus::On::Shared, 10000);
}

std::string Census::names() const {
  if (seen_.empty()) return "none";
  std::string out;
  for (const auto& [name, s] : seen_) out += (out.empty() ? "" : ", ") + name;
  if (unlisted_ > 0) out += fmt::format(" and more ({} messages on channels past the first {})", unlisted_, kMaxChannels);
  return out;
}

void Census::on(const lcm::ReceiveBuffer* rb, const std::string& channel) {
  auto it = seen_.find(channel);
  if (it == seen_.end()) {
    if (seen_.size() >= kMaxChannels) {
      ++unlisted_;
      return;
    }
    it = seen_.emplace(channel, ChannelSeen{}).first;
  }
  auto& s = it->second;
  const int64_t now = monotonic_us();
  if (s.count++ == 0) {
    s.first_us = now;
    s.type = type_name(rb->data, rb->data_size);
  }
  s.last_us = now;
  s.bytes += rb->data_size;
}

NamespaceProbe::NamespaceProbe(Bus& bus, std::vector<std::string> channels)
    : bus_(bus), channels_(std::move(channels)) {
  sub_ = bus.subscribe(".*", &NamespaceProbe::on, this, Bus::On::Shared, 1000);
}

NamespaceProbe::~NamespaceProbe() { bus_.unsubscribe(sub_); }

void NamespaceProbe::on(const lcm::ReceiveBuffer*, const std::string& channel) {
  if (ours_ || others_.size() > 1) return;
  const std::string own = bus_.channel("");
  for (const auto& c : channels_) {
    if (channel == own + c) {
      ours_ = true;
    } else if (channel == c) {
      others_.emplace("", channel);
    } else if (channel.size() > c.size() + 1 && channel.compare(channel.size() - c.size(), c.size(), c) == 0 &&
               channel[channel.size() - c.size() - 1] == '/') {
      others_.emplace(channel.substr(0, channel.size() - c.size() - 1), channel);
    }
  }
}

std::string NamespaceProbe::hint() const {
  if (ours_ || others_.size() != 1) return "";
  const auto& [ns, channel] = *others_.begin();
  if (ns.empty())
    return fmt::format("'{}' is heard without a namespace: did you mean no --namespace (and LCM_CONTROL_NAMESPACE "
                       "unset)?",
                       channel);
  return fmt::format("'{}' is heard under namespace '{}': did you mean --namespace {}?", channel, ns, ns);
}

}  // namespace lcm_control::tools
