#include "bus/endpoints.hpp"

namespace lcm_control {

Endpoints::~Endpoints() {
  for (auto* s : subs_) lc_.unsubscribe(s);
  for (const int id : socket_subs_) socket_->unsubscribe(id);
  for (const int id : shm_subs_) shm_->unsubscribe(id);
}

void Endpoints::subscribe_raw(const std::string& channel, std::function<void(const lcm::ReceiveBuffer&)> handler) {
  handlers_.push_back(std::make_unique<Handler>(Handler{std::move(handler), channel, {}, false, this}));
  if (shm_) {
    Handler* h = handlers_.back().get();
    shm_subs_.push_back(shm_->subscribe(channel, [h](const lcm::ReceiveBuffer& rb) { h->deliver(rb); }));
    return;
  }
  if (socket_) {
    Handler* h = handlers_.back().get();
    socket_subs_.push_back(socket_->subscribe(channel, [h](const lcm::ReceiveBuffer& rb) { h->deliver(rb); }));
    return;
  }
  lcm::Subscription* s = lc_.subscribe(channel, &Handler::on, handlers_.back().get());
  s->setQueueCapacity(100);
  subs_.push_back(s);
}

void Endpoints::on_lost(const std::string& channel, LcmSocket::LostHandler handler) {
  if (socket_) socket_subs_.push_back(socket_->on_lost(channel, std::move(handler)));
}

void Endpoints::divert(const std::string& channel, RawHandler to) {
  bool first = true;
  for (auto& h : handlers_) {
    if (h->channel != channel) continue;
    h->muted = to && !first;
    h->diverted = first ? to : RawHandler{};
    first = false;
  }
}

void Endpoints::hold(Handler& h, const lcm::ReceiveBuffer& rb) {
  if (held_.size() >= kHeldMax) {
    held_.pop_front();
    ++held_dropped_;
  }
  const auto* data = static_cast<const uint8_t*>(rb.data);
  held_.push_back({&h, std::vector<uint8_t>(data, data + rb.data_size), rb.recv_utime});
}

void Endpoints::deliver_result(Intake::Result result) {
  if (busy_ && busy_()) {
    held_results_.push_back(std::move(result));
  } else {
    result();
  }
}

size_t Endpoints::deliver_held() {
  size_t n = 0;
  while (!held_.empty() && !(busy_ && busy_())) {
    Held m = std::move(held_.front());
    held_.pop_front();
    lcm::ReceiveBuffer rb{m.bytes.data(), static_cast<uint32_t>(m.bytes.size()), m.recv_utime};
    m.handler->deliver(rb);
    ++n;
  }
  while (!held_results_.empty() && !(busy_ && busy_())) {
    Intake::Result r = std::move(held_results_.front());
    held_results_.pop_front();
    r();
    ++n;
  }
  return n;
}

std::vector<std::string> Endpoints::channels() const {
  std::vector<std::string> out;
  for (const auto& h : handlers_) out.push_back(h->channel);
  return out;
}

}  // namespace lcm_control
