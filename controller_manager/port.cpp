#include "controller_manager/port.hpp"

namespace lcm_control::cm {

Port::~Port() {
  for (auto* s : subs_) lc_.unsubscribe(s);
}

void Port::subscribe_raw(const std::string& channel, std::function<void(const lcm::ReceiveBuffer&)> handler) {
  handlers_.push_back(std::make_unique<Handler>(Handler{std::move(handler)}));
  lcm::Subscription* s = lc_.subscribe(channel, &Handler::on, handlers_.back().get());
  s->setQueueCapacity(100);
  subs_.push_back(s);
}

}  // namespace lcm_control::cm
