#include "controller_manager/input_stamps.hpp"

#include "bus/digest.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "rt/clock.hpp"

namespace lcm_control::cm {

InputStamps::InputStamps(Bus& bus, Publisher<cm_inputs_t> publisher)
    : bus_(bus), is_input_(bus), publisher_(std::move(publisher)) {
  if (LcmSocket* socket = bus_.shared_socket())
    socket->set_tap([this](const lcm::ReceiveBuffer& rb, const std::string& channel) {
      taken(channel, rb.data, rb.data_size);
    });
}

InputStamps::~InputStamps() {
  if (LcmSocket* socket = bus_.shared_socket()) socket->set_tap({});
}

InputFilter::InputFilter(const Bus& bus)
    : hardware_(bus.channel("hardware/")), sim_(bus.channel("sim_server/")), request_(bus.channel(channels::kCmRequest)) {}

bool InputFilter::operator()(const std::string& channel, const void* data, size_t size) const {
  if (channel.compare(0, hardware_.size(), hardware_) == 0 || channel.compare(0, sim_.size(), sim_) == 0) return false;
  if (channel == request_) {  // a query changes nothing
    cm_request_t r;
    if (decode_guarded(r, data, size) &&
        (r.op == cm_request_t::LIST || r.op == cm_request_t::LIST_TYPES || r.op == cm_request_t::CONFIG))
      return false;
  }
  return true;
}

void InputStamps::taken(const std::string& channel, const void* data, size_t size) {
  just_taken_ = false;
  if (!is_input_(channel, data, size)) return;
  just_taken_ = add({channel, static_cast<int64_t>(message_digest(data, size)), static_cast<int32_t>(size)});
}

bool InputStamps::add(Input input) {
  if (pending_.channel.size() >= kListed) {
    ++pending_.untaken;
    return false;
  }
  pending_.channel.push_back(std::move(input.channel));
  pending_.digest.push_back(input.digest);
  pending_.size.push_back(input.size);
  return true;
}

void InputStamps::submitted_off_loop() {
  if (!just_taken_) {
    deferred_.emplace_back();
    return;
  }
  just_taken_ = false;
  deferred_.push_back(Input{std::move(pending_.channel.back()), pending_.digest.back(), pending_.size.back()});
  pending_.channel.pop_back();
  pending_.digest.pop_back();
  pending_.size.pop_back();
}

void InputStamps::result_taken() {
  if (deferred_.empty()) return;
  if (deferred_.front()) add(std::move(*deferred_.front()));
  deferred_.pop_front();
}

void InputStamps::stamp(int64_t session, int64_t step) {
  if (pending_.channel.empty() && pending_.untaken == 0) return;
  pending_.utime = wall_us();
  pending_.session = session;
  pending_.step = step;
  pending_.num_inputs = static_cast<int32_t>(pending_.channel.size());
  publisher_.publish(pending_);
  pending_.channel.clear();
  pending_.digest.clear();
  pending_.size.clear();
  pending_.untaken = 0;
  just_taken_ = false;
}

}  // namespace lcm_control::cm
